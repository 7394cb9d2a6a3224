// SPDX-License-Identifier: MIT
// Reads a map through the installed sewerplan package and prints its size.
#include <iostream>

#include "sewerplan/core/map_io.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: consumer MAP\n";
    return 2;
  }
  sewerplan::Diagnostics diagnostics;
  auto map = sewerplan::read_map(argv[1], diagnostics);
  if (!map.has_value()) {
    std::cerr << map.error() << '\n';
    return 1;
  }
  std::cout << map->name() << ": " << map->manhole_count() << " manholes, " << map->pipe_count()
            << " pipes\n";
  return 0;
}
