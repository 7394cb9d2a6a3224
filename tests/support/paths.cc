// SPDX-License-Identifier: MIT
#include "support/paths.h"
