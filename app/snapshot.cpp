#include "app/snapshot.h"

#include "core/icosphere.h"
#include "core/settings_io.h"

#include <cctype>
#include <string>

namespace slime {

void applyImageSize(Settings& settings, const std::string& size) {
  constexpr long kLargest = 8192;
  const auto fail = [&] {
    return SettingsError("--size must be WxH with W and H whole numbers in 1.." + std::to_string(kLargest) +
                         " pixels, got '" + size + "'");
  };
  const std::size_t separator = size.find_first_of("xX");
  if (separator == std::string::npos) throw fail();
  const std::string widthText = size.substr(0, separator), heightText = size.substr(separator + 1);
  const auto parse = [&](const std::string& text) {
    if (text.empty() || text.size() > 6) throw fail();
    for (const char c : text)
      if (!std::isdigit(static_cast<unsigned char>(c))) throw fail();
    const long value = std::stol(text);
    if (value < 1 || value > kLargest) throw fail();
    return static_cast<int>(value);
  };
  settings.camera.width = parse(widthText);
  settings.camera.height = parse(heightText);
}

SnapshotResult takeSnapshot(const Settings& settings, double settleSeconds) {
  SnapshotResult result;
  // TODO(render): simulate with slime::Simulation once core/simulation.cpp lands; until then the
  // slime is the undeformed icosphere at its start position.
  const TriangleMesh mesh = makeIcosphere(settings.slime.level, settings.slime.radius, settings.slime.position);
  (void)settleSeconds;

  Renderer renderer(settings);
  renderer.updateSlime(mesh.positions, mesh.triangles);
  result.image.resize(settings.camera.width, settings.camera.height);
  result.stats = renderer.render(settings, result.image);
  return result;
}

}  // namespace slime
