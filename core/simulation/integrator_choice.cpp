#include "core/simulation/integrator_choice.h"

#include "core/bulk/lamb_sphere.h"

#include <cmath>
#include <numbers>

namespace slime {

double slowestJiggleHz(const SlimeSettings& slime) {
  const double r = slime.radius;
  const double density = slime.mass / (4.0 / 3.0 * std::numbers::pi * r * r * r);
  const double shearWaveSpeed = std::sqrt(slime.modulus / density);
  static const double eta = lambRoot(2, false, 0.0);  // 2.5011; the torsional modes do not depend on ν
  return eta * shearWaveSpeed / (2.0 * std::numbers::pi * r);
}

Integrator chooseIntegrator(const Settings& settings) {
  if (settings.sim.integrator != "auto") return parseIntegrator(settings.sim.integrator);
  const SlimeSettings& slime = settings.slime;
  if (slime.model == "bulk" && slowestJiggleHz(slime) > kShownJiggleHz &&
      slime.adhesion <= kUnseenAdhesionStrain * slime.modulus)
    return Integrator::Projective;
  return Integrator::SymplecticEuler;
}

}  // namespace slime
