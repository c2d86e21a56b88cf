// The meshed bar of the tensile test (app/bench/material/bench_tensile_bar.h) against oracles written here:
//  - the cylinder's mesh: every tetrahedron positive, the volume the polygon disc's area × length, and
//    conforming (each face shared by at most two tetrahedra; the free faces exactly the ends' triangles
//    and the side's quads, two each);
//  - the standard linear solid's constant-strain-rate response σ = E∞ε + E₁ε̇τ(1 − e^{−ε/(ε̇τ)}),
//    E = 2G(1 + ν) (issue 29, item 5a), within 5 % for ε ≤ 5 % at three rates, measured on the middle
//    half of the bar (an extensometer) — and faster pulls need more force;
//  - the clamps: a purely elastic bar's middle is Young's modulus with lateral contraction −νε, while its
//    grips' strain reads it stiffer by an end effect that halves when the bar is twice as long.
#include "app/bench/material/bench_tensile.h"
#include "app/bench/material/bench_tensile_bar.h"
#include "core/settings/settings_io.h"
#include "sls_oracle.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace slime {
namespace {

TEST(BenchTensileBar, CylinderMeshIsPositiveConformingAndFillsItsVolume) {
  const CylinderMesh cylinder = makeCylinderTetMesh(0.01, 0.08, 2, 16);
  EXPECT_EQ(cylinder.nodesPerLayer, 19);  // 1 + 6 + 12
  EXPECT_EQ(cylinder.mesh.positions.size(), 17u * 19u);
  EXPECT_EQ(cylinder.mesh.tetrahedra.size(), 16u * 24u * 3u);  // 6K² triangles per layer, 3 tetrahedra per prism
  // The regular 12-gon of the outer ring: 12·½R²·sin(2π/12) = 3R².
  EXPECT_NEAR(cylinder.crossSection, 6.0 * 0.01 * 0.01 * std::sin(2.0 * 3.14159265358979 / 12.0), 1e-12);
  double volume = 0.0;
  std::map<std::array<std::uint32_t, 3>, int> faces;
  const auto& x = cylinder.mesh.positions;
  for (const Tetrahedron& t : cylinder.mesh.tetrahedra) {
    const double v = tetrahedronVolume(x[t.x], x[t.y], x[t.z], x[t.w]);
    EXPECT_GT(v, 0.05 * (0.08 / 16) * cylinder.crossSection / 24.0);  // no sliver: ≥ 5 % of a prism's third
    volume += v;
    const std::array<std::uint32_t, 4> n{t.x, t.y, t.z, t.w};
    for (int skip = 0; skip < 4; ++skip) {
      std::array<std::uint32_t, 3> face{};
      for (int i = 0, k = 0; i < 4; ++i)
        if (i != skip) face[k++] = n[i];
      std::sort(face.begin(), face.end());
      ++faces[face];
    }
  }
  EXPECT_NEAR(volume, cylinder.crossSection * 0.08, 1e-12);
  int free = 0;
  for (const auto& [face, count] : faces) {
    EXPECT_LE(count, 2);
    free += count == 1 ? 1 : 0;
  }
  EXPECT_EQ(free, 2 * 24 + 12 * 16 * 2);  // two ends of 24 triangles; 12 side quads per layer, 2 triangles each
}

TEST(BenchTensileBar, MiddleFollowsTheStandardLinearSolidAtThreeRates) {
  const SlimeSettings slime = defaultSettings().slime;
  std::array<double, 3> atFivePercent{};
  const std::array<double, 3> rates{0.05, 0.5, 5.0};
  for (std::size_t r = 0; r < rates.size(); ++r) {
    const double rate = rates[r];
    const MeshedBarRun run = stretchMeshedBar(materialOf(slime), rate, 0.05, 25);
    ASSERT_EQ(run.strains.size(), 26u);
    EXPECT_NEAR(run.stresses.front(), 0.0, 1e-9);
    EXPECT_GT(run.smallestVolumeRatio, 0.95);
    int checked = 0;
    for (std::size_t k = 1; k < run.strains.size(); ++k) {
      const double gauge = run.gaugeStrains[k];
      if (gauge > 0.05) continue;
      const double oracle = fixture::standardLinearSolidStress(slime, gauge, rate * gauge / run.strains[k]);
      EXPECT_NEAR(run.stresses[k], oracle, 0.05 * oracle) << "rate " << rate << " gauge strain " << gauge;
      ++checked;
    }
    EXPECT_GE(checked, 20);
    atFivePercent[r] = run.stresses.back();
  }
  // Faster pulls need more force: the Maxwell branch has less time to relax.
  EXPECT_GT(atFivePercent[1], 1.2 * atFivePercent[0]);
  EXPECT_GT(atFivePercent[2], 1.02 * atFivePercent[1]);
}

TEST(BenchTensileBar, ClampedEndsStiffenTheGripsReadingNotTheMiddle) {
  SlimeSettings elastic = defaultSettings().slime;
  elastic.longTerm = 1.0;  // no Maxwell branch: Young's modulus E = 2G(1 + ν) at any rate
  const double young = 2.0 * elastic.modulus * (1.0 + elastic.poisson);
  const MeshedBarRun shortBar = stretchMeshedBar(materialOf(elastic), 0.5, 0.01, 4);
  MeshedBarOptions longer;
  longer.length *= 2.0;
  longer.segments *= 2;
  const MeshedBarRun longBar = stretchMeshedBar(materialOf(elastic), 0.5, 0.01, 4, longer);
  const double gauge = shortBar.gaugeStrains.back();
  EXPECT_NEAR(shortBar.stresses.back() / gauge, young, 0.02 * young);  // the middle: E
  EXPECT_NEAR(shortBar.middleWidths.back(), 1.0 - elastic.poisson * gauge, 0.001);
  const double shortExcess = shortBar.stresses.back() / (young * 0.01) - 1.0;
  const double longExcess = longBar.stresses.back() / (young * 0.01) - 1.0;
  EXPECT_GT(shortExcess, 0.03);  // L = 4 diameters: the grips read it several per cent stiffer
  EXPECT_GT(longExcess, 0.3 * shortExcess);
  EXPECT_LT(longExcess, 0.7 * shortExcess);  // an end zone of fixed length: half the excess at twice the length
}

}  // namespace
}  // namespace slime
