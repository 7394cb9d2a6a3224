// SPDX-License-Identifier: MIT
#include "sewerplan/server/basemap.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iterator>
#include <numbers>
#include <system_error>
#include <utility>

namespace sewerplan::server {
namespace {

constexpr std::array<std::string_view, 4> kTileExtensions = {"png", "jpg", "jpeg", "webp"};
// Web Mercator's limits: the square of the world.
constexpr double kMaxLatitude = 85.0511287798066;
constexpr double kEarthRadiusM = 6378137;  // the sphere of Web Mercator
constexpr double kTilePixels = 256;

bool all_digits(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return std::isdigit(static_cast<unsigned char>(c));
  });
}

// A folder's name as a zoom level (or a tile's column), if it is one: digits only, not too many.
std::optional<long long> number_of(std::string_view name, std::size_t max_digits) {
  if (!all_digits(name) || name.size() > max_digits) return std::nullopt;
  return std::stoll(std::string(name));
}

void replace_all(std::string& text, std::string_view what, const std::string& with) {
  for (std::size_t at = text.find(what); at != std::string::npos;
       at = text.find(what, at + with.size())) {
    text.replace(at, what.size(), with);
  }
}

std::string tile_url(const std::string& url_template, int z, long long x, long long y) {
  std::string url = url_template;
  replace_all(url, "{z}", std::to_string(z));
  replace_all(url, "{x}", std::to_string(x));
  replace_all(url, "{y}", std::to_string(y));
  return url;
}

Result<TileSource> url_source(std::string_view text) {
  const auto refuse = [&](const std::string& why) {
    return Error{ErrorCode::kInvalidArgument,
                 "--tiles " + std::string(text) + ": " + why +
                     " (expected an XYZ template such as https://tile.example.org/{z}/{x}/{y}.png, "
                     "or a directory of Z/X/Y.png tiles)"};
  };
  for (const char* key : {"{z}", "{x}", "{y}"}) {
    if (text.find(key) == std::string_view::npos) return refuse(std::string("no ") + key);
  }
  std::string rest(text);
  for (const char* key : {"{z}", "{x}", "{y}"}) replace_all(rest, key, "");
  if (rest.find_first_of("{}") != std::string::npos) {
    return refuse("only {z}, {x} and {y} are filled in (name one host, not {s})");
  }
  return TileSource{.kind = TileSource::Kind::kUrl, .url_template = std::string(text)};
}

Result<TileSource> directory_source(std::string_view text) {
  const std::filesystem::path dir(text);
  const auto refuse = [&](const std::string& why) {
    return Error{ErrorCode::kInvalidArgument,
                 "--tiles " + std::string(text) + ": " + why +
                     " (expected an XYZ template such as https://tile.example.org/{z}/{x}/{y}.png, "
                     "or a directory of Z/X/Y.png tiles)"};
  };
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return refuse("no such directory");
  std::vector<int> zooms;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::optional<long long> z = number_of(entry.path().filename().string(), 2);
    if (z && *z <= kMaxTileZoom && entry.is_directory(ec)) zooms.push_back(static_cast<int>(*z));
  }
  if (ec) return refuse("cannot be read (" + ec.message() + ")");
  std::sort(zooms.begin(), zooms.end());
  // The first tile found, in the lowest zoom level that has one, says the extension.
  for (const int z : zooms) {
    for (const auto& column : std::filesystem::directory_iterator(dir / std::to_string(z), ec)) {
      if (!number_of(column.path().filename().string(), 10) || !column.is_directory(ec)) continue;
      for (const auto& tile : std::filesystem::directory_iterator(column.path(), ec)) {
        const std::string ext = tile.path().extension().string();
        if (!all_digits(tile.path().stem().string()) || ext.size() < 2) continue;
        const std::string_view e = std::string_view(ext).substr(1);
        if (std::find(kTileExtensions.begin(), kTileExtensions.end(), e) == kTileExtensions.end())
          continue;
        return TileSource{.kind = TileSource::Kind::kDirectory,
                          .url_template = "api/tiles/{z}/{x}/{y}." + std::string(e),
                          .directory = dir,
                          .extension = std::string(e),
                          .min_zoom = zooms.front(),
                          .max_zoom = zooms.back()};
      }
    }
  }
  return refuse("no tiles in it (Z/X/Y.png, .jpg, .jpeg or .webp, such as 12/2127/1370.png)");
}

double tile_longitude(double x, double n) { return x / n * 360 - 180; }
double tile_latitude(double y, double n) {
  return std::atan(std::sinh(std::numbers::pi * (1 - 2 * y / n))) * 180 / std::numbers::pi;
}
double tile_column(double lon, double n) { return (lon + 180) / 360 * n; }
double tile_row(double lat, double n) {
  const double phi = std::clamp(lat, -kMaxLatitude, kMaxLatitude) * std::numbers::pi / 180;
  return (1 - std::log(std::tan(phi) + 1 / std::cos(phi)) / std::numbers::pi) / 2 * n;
}

}  // namespace

Result<TileSource> parse_tile_source(std::string_view text) {
  if (text.starts_with("http://") || text.starts_with("https://")) return url_source(text);
  if (text.find("://") != std::string_view::npos) {
    return Error{ErrorCode::kInvalidArgument,
                 "--tiles " + std::string(text) +
                     ": only http:// and https:// templates, or a local directory of Z/X/Y.png "
                     "tiles"};
  }
  return directory_source(text);
}

std::optional<std::filesystem::path> tile_file(const TileSource& source, int z, long long x,
                                               long long y, std::string_view extension) {
  if (source.kind != TileSource::Kind::kDirectory || extension != source.extension) return {};
  if (z < 0 || z > kMaxTileZoom || x < 0 || y < 0) return {};
  const long long n = 1LL << z;
  if (x >= n || y >= n) return {};
  std::filesystem::path file = source.directory / std::to_string(z) / std::to_string(x) /
                               (std::to_string(y) + "." + source.extension);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return {};
  return file;
}

std::optional<std::string> read_tile(const TileSource& source, int z, long long x, long long y,
                                     std::string_view extension) {
  const std::optional<std::filesystem::path> file = tile_file(source, z, x, y, extension);
  if (!file) return std::nullopt;
  std::ifstream in(*file, std::ios::binary);
  if (!in) return std::nullopt;
  return std::string{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

Result<TileChoice> choose_tiles(const TileSource& source, const BasemapView& view,
                                const Reprojection& reproject, std::size_t max_tiles) {
  const auto [x0, y0, x1, y1] = view.rect;
  if (!(std::isfinite(x0) && std::isfinite(y0) && std::isfinite(x1) && std::isfinite(y1) &&
        x0 < x1 && y0 < y1)) {
    return Error{ErrorCode::kInvalidArgument,
                 "the view: expected x0 < x1 and y0 < y1, finite metres"};
  }
  if (!(std::isfinite(view.metres_per_pixel) && view.metres_per_pixel > 0)) {
    return Error{ErrorCode::kInvalidArgument, "the view's metres per pixel: expected over 0"};
  }
  TileChoice choice{.zoom = source.min_zoom};
  // The view's corners, edges' middles and centre on the earth: its extent in longitude and
  // latitude (a projected CRS's grid is turned against the meridians, a little).
  std::vector<MapXY> samples;
  for (int j = 0; j <= 2; ++j) {
    for (int i = 0; i <= 2; ++i) {
      samples.push_back({.x = x0 + (x1 - x0) * i / 2, .y = y0 + (y1 - y0) * j / 2});
    }
  }
  if (Result<void> r = reproject(true, samples); !r.has_value()) return r.error();
  double lon0 = 180, lon1 = -180, lat0 = 90, lat1 = -90;
  bool any = false;
  for (const MapXY& p : samples) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
    any = true;
    lon0 = std::min(lon0, p.x);
    lon1 = std::max(lon1, p.x);
    lat0 = std::min(lat0, p.y);
    lat1 = std::max(lat1, p.y);
  }
  if (!any) {
    choice.note = "the view lies outside what the map's CRS can place on the earth";
    return choice;
  }
  lat0 = std::clamp(lat0, -kMaxLatitude, kMaxLatitude);
  lat1 = std::clamp(lat1, -kMaxLatitude, kMaxLatitude);
  const double centre_lat = (lat0 + lat1) / 2;
  // A tile pixel at level z is 2 pi R cos(lat) / (256 * 2^z) metres on the ground: the level whose
  // pixel is nearest the view's.
  const double ground = 2 * std::numbers::pi * kEarthRadiusM *
                        std::cos(centre_lat * std::numbers::pi / 180) / kTilePixels;
  const double wanted = std::log2(ground / view.metres_per_pixel);
  int z = std::clamp(static_cast<int>(std::lround(std::clamp(wanted, -1.0, 64.0))), source.min_zoom,
                     source.max_zoom);
  long long tx0 = 0, tx1 = 0, ty0 = 0, ty1 = 0;
  double n = 1;
  for (;; --z) {
    n = std::ldexp(1.0, z);
    const auto clamp_tile = [n](double t) {
      return static_cast<long long>(std::clamp(std::floor(t), 0.0, n - 1));
    };
    tx0 = clamp_tile(tile_column(lon0, n));
    tx1 = clamp_tile(tile_column(lon1, n));
    ty0 = clamp_tile(tile_row(lat1, n));  // rows count down from the north
    ty1 = clamp_tile(tile_row(lat0, n));
    const double count = static_cast<double>(tx1 - tx0 + 1) * static_cast<double>(ty1 - ty0 + 1);
    if (count <= static_cast<double>(max_tiles) || z <= source.min_zoom) break;
  }
  choice.zoom = z;
  std::vector<std::pair<long long, long long>> tiles;  // (row, column)
  // More than max_tiles only at the source's lowest level: the tiles nearest the view's centre.
  const double cx = tile_column((lon0 + lon1) / 2, n), cy = tile_row(centre_lat, n);
  const long long rows = ty1 - ty0 + 1, columns = tx1 - tx0 + 1;
  if (static_cast<double>(rows) * static_cast<double>(columns) > static_cast<double>(max_tiles)) {
    choice.truncated = true;
    const auto half = static_cast<long long>(std::ceil(std::sqrt(static_cast<double>(max_tiles))));
    const auto near = [half](double c, long long lo, long long hi) {
      const long long mid = static_cast<long long>(std::floor(c));
      return std::pair{std::max(lo, mid - half), std::min(hi, mid + half)};
    };
    std::tie(tx0, tx1) = near(cx, tx0, tx1);
    std::tie(ty0, ty1) = near(cy, ty0, ty1);
  }
  for (long long ty = ty0; ty <= ty1; ++ty) {
    for (long long tx = tx0; tx <= tx1; ++tx) tiles.emplace_back(ty, tx);
  }
  if (tiles.size() > max_tiles) {
    const auto distance = [&](const std::pair<long long, long long>& t) {
      return std::hypot(static_cast<double>(t.first) + 0.5 - cy,
                        static_cast<double>(t.second) + 0.5 - cx);
    };
    std::stable_sort(tiles.begin(), tiles.end(),
                     [&](const auto& a, const auto& b) { return distance(a) < distance(b); });
    tiles.resize(max_tiles);
    std::sort(tiles.begin(), tiles.end());
  }
  // Each tile's corners, top left, top right, bottom right, bottom left, to the map's metres.
  std::vector<MapXY> corners;
  corners.reserve(tiles.size() * 4);
  for (const auto& [ty, tx] : tiles) {
    const auto x = static_cast<double>(tx), y = static_cast<double>(ty);
    for (const auto& [dx, dy] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 1}}) {
      corners.push_back({.x = tile_longitude(x + dx, n), .y = tile_latitude(y + dy, n)});
    }
  }
  if (Result<void> r = reproject(false, corners); !r.has_value()) return r.error();
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    PlacedTile placed{.z = z, .x = tiles[t].second, .y = tiles[t].first};
    bool finite = true;
    for (std::size_t c = 0; c < 4; ++c) {
      placed.corners[c] = corners[t * 4 + c];
      finite = finite && std::isfinite(placed.corners[c].x) && std::isfinite(placed.corners[c].y);
    }
    if (!finite) continue;  // a tile partly outside the CRS's domain: not placed
    placed.url = tile_url(source.url_template, z, placed.x, placed.y);
    choice.tiles.push_back(std::move(placed));
  }
  if (choice.tiles.empty()) {
    choice.note = "no tile of the view can be placed in the map's CRS";
  }
  return choice;
}

Result<TileChoice> basemap_tiles(const SewerMap& map, const TileSource& source,
                                 const BasemapView& view, const StationGis& gis,
                                 std::size_t max_tiles) {
  if (!map.crs()) {
    return Error{ErrorCode::kInvalidArgument,
                 "map " + map.name() +
                     " names no coordinate reference system (local coordinates): it cannot be "
                     "placed on a basemap; give its file one (a map JSON's \"crs\", or sewerplan "
                     "convert --crs EPSG:NNNN)"};
  }
  if (!gis.reproject) {
#if SEWERPLAN_WITH_GIS
    return Error{ErrorCode::kUnsupportedFormat,
                 "the basemap needs PROJ, but this station was given no GIS (ServerOptions::gis)"};
#else
    return Error{ErrorCode::kUnsupportedFormat,
                 "this build has no GIS (SEWERPLAN_WITH_GIS=OFF): no basemap"};
#endif
  }
  const Crs crs = *map.crs();
  return choose_tiles(
      source, view,
      [&](bool to_wgs84, std::span<MapXY> points) { return gis.reproject(crs, to_wgs84, points); },
      max_tiles);
}

}  // namespace sewerplan::server
