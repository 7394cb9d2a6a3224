// SPDX-License-Identifier: MIT
#include "sewerplan/modules/png.h"

#include <memory>
#include <string>

#include "sewerplan/modules/module.h"
#include "sewerplan/modules/png_table.h"

namespace sewerplan::modules {

Result<std::string> render_map_png(const render::RenderInput& input) {
  static const std::string stamp = png_stamp();
  Result<const PngTable*> table = load_module_table<PngTable>(kPngModule, stamp);
  if (!table.has_value()) {
    return Error{table.error().code, "a PNG picture needs cairo, but " + table.error().message};
  }
  const std::unique_ptr<render::Canvas> png = (*table)->make_png_canvas();
  return render::draw_map(input, *png);
}

}  // namespace sewerplan::modules
