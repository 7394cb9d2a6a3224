// SPDX-License-Identifier: MIT
// libFuzzer target: GIS features to a map (core/map_features.h) and the field mapping file. The
// features are synthetic, made from the input bytes: GDAL is not in the fuzz tree (it is linked by
// gis/ only), so this fuzzes everything after GDAL has read a layer: field lookup, values of any
// type, geometries of any kind, joins by field and by distance, and the layer choice.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sewerplan/core/map_features.h"

#include <fuzzer/FuzzedDataProvider.h>

namespace {

using sewerplan::GisFeature;
using sewerplan::GisGeometry;
using sewerplan::GisLayer;

// Field names the defaults know (some cut to a Shapefile's 10 characters), and a few they do not.
const char* const kFields[] = {"identifier",
                               "name",
                               "wn_obj_id",
                               "ws_type",
                               "exit",
                               "co_level",
                               "wn_bottom_level",
                               "_depth",
                               "ma_dimension1",
                               "ma_dimensi",
                               "ma_dimension2",
                               "rp_from_fk",
                               "rp_to_fk_wastewater_networkelement",
                               "from",
                               "to",
                               "rp_from_level",
                               "to_level",
                               "clear_height",
                               "height_m",
                               "width",
                               "diameter_m",
                               "shape",
                               "length_effective",
                               "length",
                               "remark"};
const char* const kTexts[] = {"M1",  "M2", "M3",  "manhole", "egg",  "1",
                              "0.5", "",   "nan", "-3",      "true", "x"};

GisLayer make_layer(FuzzedDataProvider& in, const std::string& name) {
  GisLayer layer{.name = name};
  const std::size_t fields = in.ConsumeIntegralInRange<std::size_t>(0, 8);
  for (std::size_t i = 0; i < fields; ++i) layer.fields.push_back(in.PickValueInArray(kFields));
  const std::size_t features = in.ConsumeIntegralInRange<std::size_t>(0, 12);
  for (std::size_t k = 0; k < features && in.remaining_bytes() > 0; ++k) {
    GisFeature f{.fid = static_cast<std::int64_t>(k)};
    f.geometry = static_cast<GisGeometry>(in.ConsumeIntegralInRange<int>(0, 3));
    f.geometry_name = "Geometry";
    f.has_z = in.ConsumeBool();
    const std::size_t points = in.ConsumeIntegralInRange<std::size_t>(0, 4);
    for (std::size_t p = 0; p < points; ++p) {
      if (in.ConsumeBool()) {
        f.points.push_back({in.ConsumeIntegralInRange<int>(-8, 8) * 0.5,
                            in.ConsumeIntegralInRange<int>(-8, 8) * 0.5,
                            in.ConsumeIntegralInRange<int>(-4, 4) * 0.25});
      } else {
        f.points.push_back({in.ConsumeFloatingPoint<double>(), in.ConsumeFloatingPoint<double>(),
                            in.ConsumeFloatingPoint<double>()});
      }
    }
    for (std::size_t i = 0; i < layer.fields.size(); ++i) {
      switch (in.ConsumeIntegralInRange<int>(0, 3)) {
        case 0:
          f.values.emplace_back();
          break;
        case 1:
          f.values.emplace_back(in.ConsumeFloatingPoint<double>());
          break;
        case 2:
          f.values.emplace_back(in.ConsumeIntegralInRange<int>(-2, 2000) * 1.0);
          break;
        default:
          f.values.emplace_back(in.ConsumeBool() ? std::string(in.PickValueInArray(kTexts))
                                                 : in.ConsumeRandomLengthString(12));
      }
    }
    layer.features.push_back(std::move(f));
  }
  return layer;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  sewerplan::GisFieldMapping mapping = sewerplan::GisFieldMapping::defaults();
  if (in.ConsumeBool()) {
    sewerplan::Diagnostics d;
    const std::string text = in.ConsumeRandomLengthString(400);
    auto read = sewerplan::parse_gis_field_mapping(text, "fuzz.fields.json", d);
    if (read.has_value()) mapping = std::move(*read);
  }
  mapping.tolerance_m = in.ConsumeFloatingPointInRange<double>(0, 4);
  std::vector<sewerplan::GisLayerInfo> infos;
  const std::size_t n = in.ConsumeIntegralInRange<std::size_t>(0, 4);
  for (std::size_t i = 0; i < n; ++i) {
    infos.push_back({.name = in.PickValueInArray({"manholes", "pipes", "a", "b"}),
                     .geometry = static_cast<GisGeometry>(in.ConsumeIntegralInRange<int>(0, 3)),
                     .features = in.ConsumeIntegralInRange<std::size_t>(0, 2)});
  }
  (void)sewerplan::choose_gis_layers(infos, mapping, "fuzz.gpkg", "a");
  const GisLayer manholes = make_layer(in, "manholes");
  GisLayer pipes = make_layer(in, "pipes");
  sewerplan::Diagnostics diagnostics;
  (void)sewerplan::map_from_gis_layers(manholes, pipes, mapping, "fuzz.gpkg", "fuzz", diagnostics);
  return 0;
}
