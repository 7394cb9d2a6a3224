// SPDX-License-Identifier: MIT
#include "sewerplan/gis/wgs84_projection.h"

#include <array>
#include <cmath>
#include <numbers>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tm_reference.h"

namespace sewerplan::gis {
namespace {

Crs epsg(std::uint32_t code) { return {.authority = "EPSG", .code = code}; }

// Places in Germany, longitude and latitude.
constexpr std::array<std::array<double, 2>, 4> kPlaces{{
    {9.0, 52.0},        // on UTM 32's central meridian
    {7.6261, 51.9607},  // Münster
    {10.5, 53.5},       // east of the meridian
    {8.5324, 52.0302},  // Bielefeld
}};

TEST(Wgs84Projection, Utm32AgreesWithAnIndependentTransverseMercator) {
  Result<Wgs84Projection> utm = Wgs84Projection::create(epsg(25832));
  ASSERT_TRUE(utm.has_value()) << utm.error();
  for (const auto& [lon, lat] : kPlaces) {
    const testing::EastNorth expected = testing::transverse_mercator(testing::kUtm32, lon, lat);
    Result<MapXY> xy = utm->from_wgs84(lon, lat);
    ASSERT_TRUE(xy.has_value()) << xy.error();
    EXPECT_NEAR(xy->x, expected.east, 0.01) << lon << ", " << lat;
    EXPECT_NEAR(xy->y, expected.north, 0.01) << lon << ", " << lat;
    // And back: longitude first, within a millimetre (1e-8 degrees).
    Result<LonLat> back = utm->to_wgs84(expected.east, expected.north);
    ASSERT_TRUE(back.has_value()) << back.error();
    EXPECT_NEAR(back->lon_deg, lon, 1e-8);
    EXPECT_NEAR(back->lat_deg, lat, 1e-8);
  }
}

TEST(Wgs84Projection, GaussKruegerZone3RoundTripsAndLiesWhereTheZoneSays) {
  Result<Wgs84Projection> gk = Wgs84Projection::create(epsg(31467));
  ASSERT_TRUE(gk.has_value()) << gk.error();
  for (const auto& [lon, lat] : kPlaces) {
    Result<MapXY> xy = gk->from_wgs84(lon, lat);
    ASSERT_TRUE(xy.has_value()) << xy.error();
    // DHDN is another datum: the Bessel projection of the WGS84 angles misses by the datum shift,
    // some tens to a couple of hundred metres, never by a zone or an axis swap.
    const testing::EastNorth bessel =
        testing::transverse_mercator(testing::kGaussKruger3, lon, lat);
    EXPECT_NEAR(xy->x, bessel.east, 300) << lon << ", " << lat;
    EXPECT_NEAR(xy->y, bessel.north, 300) << lon << ", " << lat;
    Result<LonLat> back = gk->to_wgs84(xy->x, xy->y);
    ASSERT_TRUE(back.has_value()) << back.error();
    EXPECT_NEAR(back->lon_deg, lon, 1e-8);
    EXPECT_NEAR(back->lat_deg, lat, 1e-8);
  }
}

// A map's x and y are metres; EPSG:2229 counts US survey feet: the projection converts, so a
// point 1000 m east of another lies 1000 m east on the globe, not 304.8 m.
TEST(Wgs84Projection, ACrsInFeetTakesTheMapsMetres) {
  Result<Wgs84Projection> feet = Wgs84Projection::create(epsg(2229));
  ASSERT_TRUE(feet.has_value()) << feet.error().message;
  constexpr double kFtUs = 1200.0 / 3937.0;
  const double x_m = 6480000 * kFtUs, y_m = 1840000 * kFtUs;
  Result<LonLat> a = feet->to_wgs84(x_m, y_m);
  Result<LonLat> b = feet->to_wgs84(x_m + 1000, y_m);
  ASSERT_TRUE(a.has_value() && b.has_value());
  // About 34 degrees north: a degree of longitude is about 92.4 km.
  const double east_m =
      (b->lon_deg - a->lon_deg) * 111320 * std::cos(a->lat_deg * std::numbers::pi / 180);
  EXPECT_NEAR(east_m, 1000, 5);
  Result<MapXY> back = feet->from_wgs84(a->lon_deg, a->lat_deg);
  ASSERT_TRUE(back.has_value());
  EXPECT_NEAR(back->x, x_m, 1e-3);
  EXPECT_NEAR(back->y, y_m, 1e-3);
}

TEST(Wgs84Projection, AnUnknownCodeIsAnErrorNamingIt) {
  Result<Wgs84Projection> none = Wgs84Projection::create(epsg(999999));
  ASSERT_FALSE(none.has_value());
  EXPECT_EQ(none.error().code, ErrorCode::kInvalidArgument);
  EXPECT_THAT(none.error().message, ::testing::HasSubstr("EPSG:999999"));
}

}  // namespace
}  // namespace sewerplan::gis
