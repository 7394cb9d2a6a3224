// SPDX-License-Identifier: MIT
// The station's basemap (server/basemap.h): the tile source `serve --tiles` names, the tiles chosen
// and placed for a view (with a Web Mercator map of its own, no PROJ, and through PROJ on a UTM
// map), and the tile route's refusals: bad paths, missing tiles, traversal, no source.
#include "sewerplan/server/basemap.h"

#include <cmath>
#include <fstream>
#include <numbers>
#include <string>

#include "station_fixture.h"
#include <unistd.h>

namespace sewerplan::server {
namespace {

constexpr double kR = 6378137;  // Web Mercator's sphere
constexpr double kPi = std::numbers::pi;

// A map whose metres are Web Mercator's own: the tiles' corners are known exactly.
Result<void> mercator(bool to_wgs84, std::span<MapXY> points) {
  for (MapXY& p : points) {
    if (to_wgs84) {
      p = {.x = p.x / kR * 180 / kPi,
           .y = (2 * std::atan(std::exp(p.y / kR)) - kPi / 2) * 180 / kPi};
    } else {
      p = {.x = p.x * kPi / 180 * kR, .y = std::log(std::tan(kPi / 4 + p.y * kPi / 360)) * kR};
    }
  }
  return {};
}

// Metres a tile pixel is at level z at the equator.
double pixel_at(int z) { return 2 * kPi * kR / 256 / std::ldexp(1.0, z); }

TileSource url(int min_zoom = 0, int max_zoom = 19) {
  return {.kind = TileSource::Kind::kUrl,
          .url_template = "https://t.example.org/{z}/{x}/{y}.png",
          .min_zoom = min_zoom,
          .max_zoom = max_zoom};
}

TEST(ChooseTilesTest, TakesTheLevelWhosePixelIsTheViewsAndCoversTheView) {
  const BasemapView view{{1000, 2000, 1000 + 800 * pixel_at(16), 2000 + 500 * pixel_at(16)},
                         pixel_at(16) * 1.2};
  Result<TileChoice> choice = choose_tiles(url(), view, mercator);
  ASSERT_TRUE(choice.has_value()) << choice.error();
  EXPECT_EQ(choice->zoom, 16);
  EXPECT_FALSE(choice->truncated);
  const double side = 256 * pixel_at(16), n = 65536;
  double x0 = 1e18, y0 = 1e18, x1 = -1e18, y1 = -1e18;
  for (const PlacedTile& t : choice->tiles) {
    EXPECT_EQ(t.url, "https://t.example.org/16/" + std::to_string(t.x) + "/" + std::to_string(t.y) +
                         ".png");
    // Top left, top right, bottom right, bottom left: the tile's own square in Web Mercator.
    const double left = (static_cast<double>(t.x) - n / 2) * side;
    const double top = (n / 2 - static_cast<double>(t.y)) * side;
    const std::array<MapXY, 4> expected = {MapXY{left, top}, MapXY{left + side, top},
                                           MapXY{left + side, top - side}, MapXY{left, top - side}};
    for (std::size_t c = 0; c < 4; ++c) {
      EXPECT_NEAR(t.corners[c].x, expected[c].x, 1e-6);
      EXPECT_NEAR(t.corners[c].y, expected[c].y, 1e-6);
    }
    x0 = std::min(x0, left), x1 = std::max(x1, left + side);
    y0 = std::min(y0, top - side), y1 = std::max(y1, top);
  }
  // 800 x 500 pixels of the view: 4 or 5 columns and 2 or 3 rows of 256-pixel tiles, covering it.
  EXPECT_GE(choice->tiles.size(), 8u);
  EXPECT_LE(choice->tiles.size(), 15u);
  EXPECT_LE(x0, view.rect[0]);
  EXPECT_LE(y0, view.rect[1]);
  EXPECT_GE(x1, view.rect[2]);
  EXPECT_GE(y1, view.rect[3]);
}

TEST(ChooseTilesTest, KeepsToTheSourcesLevelsAndLowersTheLevelForAWideView) {
  const BasemapView close{{0, 0, 100, 100}, 0.01};
  EXPECT_EQ(choose_tiles(url(3, 12), close, mercator)->zoom, 12);
  const BasemapView far{{0, 0, 1e6, 1e6}, 1e5};
  EXPECT_EQ(choose_tiles(url(3, 12), far, mercator)->zoom, 3);
  // 1,000 km at 1 m a pixel: level 17 would need 26,000 tiles; lowered until 64 do.
  Result<TileChoice> wide = choose_tiles(url(), {{0, 0, 1e6, 1e6}, 1}, mercator);
  ASSERT_TRUE(wide.has_value());
  EXPECT_LE(wide->tiles.size(), 64u);
  EXPECT_FALSE(wide->truncated);
  EXPECT_LT(wide->zoom, 17);
  // A source with one level: the tiles nearest the view's centre, said to be cut.
  Result<TileChoice> cut = choose_tiles(url(12, 12), {{0, 0, 1e6, 1e6}, 1}, mercator, 16);
  ASSERT_TRUE(cut.has_value());
  EXPECT_TRUE(cut->truncated);
  EXPECT_EQ(cut->tiles.size(), 16u);
  const double centre_column = (5e5 / (256 * pixel_at(12))) + 2048;
  for (const PlacedTile& t : cut->tiles)
    EXPECT_LT(std::abs(static_cast<double>(t.x) + 0.5 - centre_column), 3.0);
}

TEST(ChooseTilesTest, RefusesABadViewAndSaysWhenNothingCanBePlaced) {
  EXPECT_FALSE(choose_tiles(url(), {{10, 0, 0, 10}, 1}, mercator).has_value());
  EXPECT_FALSE(choose_tiles(url(), {{0, 0, 10, 10}, 0}, mercator).has_value());
  EXPECT_FALSE(choose_tiles(url(), {{0, 0, NAN, 10}, 1}, mercator).has_value());
  const Reprojection nowhere = [](bool, std::span<MapXY> points) -> Result<void> {
    for (MapXY& p : points) p = {NAN, NAN};
    return {};
  };
  Result<TileChoice> none = choose_tiles(url(), {{0, 0, 10, 10}, 1}, nowhere);
  ASSERT_TRUE(none.has_value());
  EXPECT_TRUE(none->tiles.empty());
  EXPECT_NE(none->note.find("outside what the map's CRS"), std::string::npos);
  const Reprojection unknown = [](bool, std::span<MapXY>) -> Result<void> {
    return Error{ErrorCode::kInvalidArgument, "CRS EPSG:1: PROJ does not know it"};
  };
  EXPECT_FALSE(choose_tiles(url(), {{0, 0, 10, 10}, 1}, unknown).has_value());
}

// A directory of tiles for a test: Z/X/Y.png files with bytes no text reader keeps as they are.
class TileDirectory {
 public:
  TileDirectory()
      : root_(std::filesystem::temp_directory_path() /
              ("sewerplan-tiles-" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(root_);
  }
  ~TileDirectory() { std::filesystem::remove_all(root_); }
  void add(const std::string& relative, const std::string& bytes) {
    const std::filesystem::path file = root_ / relative;
    std::filesystem::create_directories(file.parent_path());
    std::ofstream(file, std::ios::binary) << bytes;
  }
  const std::filesystem::path& root() const { return root_; }

 private:
  std::filesystem::path root_;
};

const std::string kPngBytes("\x89PNG\r\n\x1a\n\0\xff\xfe\r\n", 13);

TEST(TileSourceTest, ReadsAUrlTemplateOrADirectoryAndRefusesAnythingElse) {
  Result<TileSource> web = parse_tile_source("https://tile.example.org/{z}/{x}/{y}.png");
  ASSERT_TRUE(web.has_value()) << web.error();
  EXPECT_EQ(web->kind, TileSource::Kind::kUrl);
  EXPECT_EQ(web->max_zoom, 19);
  for (const char* bad :
       {"https://tile.example.org/{z}/{x}.png", "https://{s}.tile.example.org/{z}/{x}/{y}.png",
        "ftp://tile.example.org/{z}/{x}/{y}.png", "/no/such/tiles"}) {
    Result<TileSource> refused = parse_tile_source(bad);
    ASSERT_FALSE(refused.has_value()) << bad;
    EXPECT_NE(refused.error().message.find(bad), std::string::npos) << refused.error().message;
  }
  TileDirectory dir;
  dir.add("README", "not a tile");
  Result<TileSource> empty = parse_tile_source(dir.root().string());
  ASSERT_FALSE(empty.has_value());
  EXPECT_NE(empty.error().message.find("no tiles in it"), std::string::npos);
  dir.add("12/2127/1370.jpg", kPngBytes);
  dir.add("14/8510/5481.jpg", kPngBytes);
  dir.add("notes/1/1.jpg", kPngBytes);
  Result<TileSource> local = parse_tile_source(dir.root().string());
  ASSERT_TRUE(local.has_value()) << local.error();
  EXPECT_EQ(local->kind, TileSource::Kind::kDirectory);
  EXPECT_EQ(local->extension, "jpg");
  EXPECT_EQ(local->url_template, "api/tiles/{z}/{x}/{y}.jpg");
  EXPECT_EQ(local->min_zoom, 12);
  EXPECT_EQ(local->max_zoom, 14);
  EXPECT_EQ(read_tile(*local, 12, 2127, 1370, "jpg"), kPngBytes);
  EXPECT_FALSE(read_tile(*local, 12, 2127, 1370, "png"));  // not the source's extension
  EXPECT_FALSE(read_tile(*local, 12, 2127, 1371, "jpg"));  // not there
  EXPECT_FALSE(read_tile(*local, 2, 4, 0, "jpg"));         // x past 2^z
  EXPECT_FALSE(read_tile(*local, 31, 0, 0, "jpg"));        // past any level
}

class BasemapApiTest : public StationFixture {
 protected:
  // The AIS map, and a copy of it that names ETRS89 / UTM 32N (so on the equator, 500 km west of
  // the zone's central meridian).
  void start_with(const std::string& tiles, const std::string& token = "") {
    std::string utm = read(kAis / "map.json");
    utm.insert(utm.find('{') + 1, R"("crs": "EPSG:25832",)");
    utm_ = std::filesystem::temp_directory_path() /
           ("sewerplan-basemap-maps-" + std::to_string(::getpid()));
    std::filesystem::create_directories(utm_);
    const std::filesystem::path file = utm_ / "utm.json";
    std::ofstream(file) << utm;
    start({.maps = {kAis / "map.json", file}, .token = token, .tiles = tiles});
  }
  void TearDown() override {
    StationFixture::TearDown();
    if (!utm_.empty()) std::filesystem::remove_all(utm_);
  }
  int status_of(const std::string& path) {
    auto r = client_->Get(path.c_str());
    EXPECT_TRUE(r) << path;
    return r ? r->status : 0;
  }
  TileDirectory dir_;
  std::filesystem::path utm_;
};

TEST_F(BasemapApiTest, ManualServesTheTilesOfADirectoryAndNothingElse) {
  dir_.add("12/2127/1370.png", kPngBytes);
  start_with(dir_.root().string());
  auto [listed, maps] = get("/api/maps");
  ASSERT_EQ(listed, 200);
  EXPECT_EQ(maps["basemap"], (json{{"kind", "directory"},
                                   {"tiles", "api/tiles/{z}/{x}/{y}.png"},
                                   {"min_zoom", 12},
                                   {"max_zoom", 12}}));
  auto tile = client_->Get("/api/tiles/12/2127/1370.png");
  ASSERT_TRUE(tile);
  EXPECT_EQ(tile->status, 200);
  EXPECT_EQ(tile->get_header_value("Content-Type"), "image/png");
  EXPECT_EQ(tile->body, kPngBytes);  // byte for byte: no text decoding
  auto [missing, why] = get("/api/tiles/12/2127/1371.png");
  EXPECT_EQ(missing, 404);
  EXPECT_EQ(why["error"]["message"], "no tile 12/2127/1371.png");
  for (const char* bad :
       {"/api/tiles/12/2127/1370.jpg", "/api/tiles/12/9999/1370.png", "/api/tiles/99/0/0.png",
        "/api/tiles/12/2127/1370", "/api/tiles/12/2127/-1.png", "/api/tiles/12/2127/1370.png.bak",
        "/api/tiles/12/2127/../2127/1370.png", "/api/tiles/12/2127/%2e%2e/2127/1370.png",
        "/api/tiles/12/x/1370.png", "/api/tiles/12/99999999999/1370.png",
        "/api/tiles/../../../etc/passwd",
        "/api/tiles/12/2127/1370.png/../../../../../etc/passwd"}) {
    EXPECT_EQ(status_of(bad), 404) << bad;
  }
}

TEST_F(BasemapApiTest, ManualPlacesTheViewsTilesOnAMapWithACrs) {
  start_with("https://tile.example.org/{z}/{x}/{y}.png");
  // The UTM copy at x 0 to 33, y 0 to 24 (on the equator): a view of 60 x 40 m, 0.1 m a pixel.
  auto [status, tiles] = get("/api/maps/utm/basemap?x0=-10&y0=-5&x1=50&y1=35&mpp=0.1");
  ASSERT_EQ(status, 200) << tiles.dump();
  EXPECT_EQ(tiles["crs"], "EPSG:25832");
  EXPECT_EQ(tiles["zoom"], 19);  // the web's deepest level of the URL source
  ASSERT_FALSE(tiles["tiles"].empty());
  for (const json& t : tiles["tiles"]) {
    EXPECT_EQ(t["url"], "https://tile.example.org/19/" + std::to_string(t["x"].get<long long>()) +
                            "/" + std::to_string(t["y"].get<long long>()) + ".png");
    // A tile of level 19 at the equator (UTM's y 0) is 76 m a side, north up, in the map's metres
    // (a little more: UTM's scale 500 km west of its central meridian).
    const json& c = t["corners"];
    const double width = c[1][0].get<double>() - c[0][0].get<double>();
    const double height = c[0][1].get<double>() - c[3][1].get<double>();
    // Not quite square: Web Mercator puts the ellipsoid's latitudes on a sphere (1 - e^2 at the
    // equator, 0.67 %).
    EXPECT_NEAR(height / width, 1, 0.01);
    EXPECT_GT(width, 40);
    EXPECT_LT(width, 80);
  }
  // The AIS map names no CRS; a view that is not one; a map with no such ID.
  auto [local, why] = get("/api/maps/map/basemap?x0=0&y0=0&x1=10&y1=10&mpp=0.1");
  EXPECT_EQ(local, 422);
  EXPECT_NE(why["error"]["message"].get<std::string>().find("names no coordinate reference system"),
            std::string::npos);
  EXPECT_EQ(get("/api/maps/utm/basemap?x0=0&y0=0&x1=10&mpp=0.1").first, 400);
  EXPECT_EQ(get("/api/maps/utm/basemap?x0=0&y0=0&x1=10&y1=10&mpp=nan").first, 400);
  EXPECT_EQ(get("/api/maps/utm/basemap?x0=10&y0=0&x1=0&y1=10&mpp=1").first, 400);
  EXPECT_EQ(get("/api/maps/nope/basemap?x0=0&y0=0&x1=10&y1=10&mpp=1").first, 404);
  // A URL source has no tiles of the station's own.
  EXPECT_EQ(status_of("/api/tiles/19/0/0.png"), 404);
}

TEST_F(BasemapApiTest, ManualWithoutTilesHasNoBasemapAndATokenGuardsTheTiles) {
  start_with("");
  auto [listed, maps] = get("/api/maps");
  EXPECT_TRUE(maps["basemap"].is_null());
  auto [none, why] = get("/api/maps/utm/basemap?x0=0&y0=0&x1=10&y1=10&mpp=1");
  EXPECT_EQ(none, 404);
  EXPECT_NE(why["error"]["message"].get<std::string>().find("without --tiles"), std::string::npos);
  EXPECT_EQ(status_of("/api/tiles/12/2127/1370.png"), 404);
  TearDown();
  dir_.add("12/2127/1370.png", kPngBytes);
  start_with(dir_.root().string(), "s3cret");
  EXPECT_EQ(status_of("/api/tiles/12/2127/1370.png"), 401);
  auto tile = client_->Get("/api/tiles/12/2127/1370.png", {{"Authorization", "Bearer s3cret"}});
  ASSERT_TRUE(tile);
  EXPECT_EQ(tile->status, 200);
}

TEST_F(BasemapApiTest, ManualRefusesToStartWithABadTileSource) {
  ServerOptions options{.maps = {kAis / "map.json"}, .tiles = "/no/such/tiles"};
  Result<std::unique_ptr<StationServer>> created = StationServer::create(options);
  ASSERT_FALSE(created.has_value());
  EXPECT_NE(created.error().message.find("--tiles /no/such/tiles: no such directory"),
            std::string::npos)
      << created.error().message;
}

}  // namespace
}  // namespace sewerplan::server
