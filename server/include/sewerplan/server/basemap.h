// SPDX-License-Identifier: MIT
// The station's optional basemap (docs/operator-station.md, "The basemap"): street-map tiles under
// the network, from a tile source the operator names with `serve --tiles SRC`, off by default.
//
// A tile source is an XYZ URL template ("https://tile.example.org/{z}/{x}/{y}.png", fetched by the
// browser) or a local directory of Z/X/Y.png files (served by the station at /api/tiles/: the
// station runs where no internet may be reachable). Tiles are Web Mercator (EPSG:3857), 256
// pixels; the map is drawn in its own metres (its CRS). So the tiles are chosen and placed here,
// for a view of the map: the view's points to longitude and latitude, the zoom level whose
// tile pixels are nearest the view's metres per pixel, the tiles that cover the view, and each
// tile's four corners from longitude and latitude back to the map's metres, through PROJ (the
// program's StationGis::reproject, station_gis.h: the command's loads the GIS module the first time
// a page asks). The page draws each tile as two
// triangles, each with the affine transform its three corners give (web/src/basemap.js).
//
//   Result<TileSource> source = parse_tile_source("tiles/");             // Z/X/Y.png below it
//   Result<TileChoice> tiles = basemap_tiles(map, *source, {{x0, y0, x1, y1}, 0.25}, gis);
//
// Thread safety: plain values and functions; basemap_tiles calls gis.reproject (station_gis.h).
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/route_geometry.h"
#include "sewerplan/server/station_gis.h"

namespace sewerplan::server {

using domain::MapXY;

struct TileSource {
  enum class Kind { kUrl, kDirectory };
  Kind kind = Kind::kUrl;
  // The tiles' address with {z}, {x} and {y}: the URL given, or the station's own
  // "api/tiles/{z}/{x}/{y}.EXT" for a directory (relative to the page, as its other requests).
  std::string url_template;
  std::filesystem::path directory;  // kDirectory: Z/X/Y.EXT below it
  std::string extension;            // kDirectory: "png", "jpg", "jpeg" or "webp", as found in it
  int min_zoom = 0;                 // kDirectory: the zoom levels (folders) it has; a URL: 0 to 19
  int max_zoom = 19;
};

// The deepest zoom level a tile may have: 2^30 tiles a side, past any source's.
inline constexpr int kMaxTileZoom = 30;

// `text` as a tile source: an http:// or https:// URL with {z}, {x} and {y} (no other {...}), or a
// directory with zoom folders (digits) holding X/Y.EXT tiles, all of one extension (the first tile
// found says which). An error that quotes `text` and says what is expected otherwise.
Result<TileSource> parse_tile_source(std::string_view text);

// The file of tile z/x/y with `extension` in a directory source, if it is one of its tiles: z up to
// kMaxTileZoom, x and y below 2^z, the source's extension, a regular file. Nothing else is read.
std::optional<std::filesystem::path> tile_file(const TileSource& source, int z, long long x,
                                               long long y, std::string_view extension);
// That file's bytes, as they are (no text decoding), if it is a tile and reads.
std::optional<std::string> read_tile(const TileSource& source, int z, long long x, long long y,
                                     std::string_view extension);

// A view of the map: its rectangle in the map's metres and how many metres a pixel is.
struct BasemapView {
  std::array<double, 4> rect{};  // x0, y0, x1, y1
  double metres_per_pixel = 1;
};

// A tile placed on the map: its corners in the map's metres, in the image's order: top left, top
// right, bottom right, bottom left (the image's pixels (0, 0), (w, 0), (w, h), (0, h)).
struct PlacedTile {
  int z = 0;
  long long x = 0;
  long long y = 0;
  std::string url;  // the source's template filled in
  std::array<MapXY, 4> corners{};
};

struct TileChoice {
  int zoom = 0;  // the level chosen (within the source's)
  std::vector<PlacedTile> tiles;
  bool truncated = false;  // more tiles cover the view than `max_tiles`: those nearest its centre
  std::string note;        // why no tile covers the view, when none does
};

// Points between the map's metres and WGS84 longitude, latitude (x, y), in place; a point that
// cannot be transformed becomes NaN (StationGis::reproject for the map's CRS).
using Reprojection = std::function<Result<void>(bool to_wgs84, std::span<MapXY> points)>;

// The tiles of `source` that cover `view`, at the zoom level whose pixel is nearest the view's
// (clamped to the source's levels; lower while more than `max_tiles` would be needed), each with
// its corners in the map's metres. A kInvalidArgument error for a view that is not a rectangle of
// finite metres with a pixel size over 0.
Result<TileChoice> choose_tiles(const TileSource& source, const BasemapView& view,
                                const Reprojection& reproject, std::size_t max_tiles = 64);

// choose_tiles through gis.reproject (PROJ), for `map`'s CRS: an error naming the map when it has
// none (local coordinates cannot be placed on the earth), when PROJ does not know its CRS, or when
// there is no GIS (this build has none, or gis.reproject is empty; else its own error).
Result<TileChoice> basemap_tiles(const SewerMap& map, const TileSource& source,
                                 const BasemapView& view, const StationGis& gis,
                                 std::size_t max_tiles = 64);

}  // namespace sewerplan::server
