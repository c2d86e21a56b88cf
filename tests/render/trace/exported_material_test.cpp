// The exported material (core/export/export_material.h) absorbs as the renderer does: glTF's
// σ = −ln(attenuationColor) / attenuationDistance equals render/trace/optics.h's absorptionCoefficients
// for the same colour and absorption, dark channels included. If the renderer's mapping changes, the
// exports must follow, and this test says so.
#include "core/export/export_material.h"
#include "render/trace/optics.h"

#include <gtest/gtest.h>

namespace slime {
namespace {

TEST(ExportedMaterial, AbsorbsPerMetreAsTheRendererDoes) {
  for (const glm::dvec3 color :
       {glm::dvec3(0.25, 0.85, 0.35), glm::dvec3(1.0, 0.5, 0.0), glm::dvec3(0.9, 0.95, 1.0)})
    for (const double absorption : {0.0, 2.0, 20.0, 500.0}) {
      SlimeSettings slime;
      slime.color = color;
      slime.absorption = absorption;
      const glm::dvec3 exported = exportMaterialOf(slime).absorptionPerMetre();
      const glm::vec3 rendered = absorptionCoefficients(glm::vec3(color), static_cast<float>(absorption));
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(exported[c], rendered[c], 1e-5 * (1.0 + rendered[c]))
            << "colour channel " << c << " = " << color[c] << ", absorption " << absorption << " /m";
    }
}

}  // namespace
}  // namespace slime
