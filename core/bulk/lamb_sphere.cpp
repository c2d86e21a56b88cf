#include "core/bulk/lamb_sphere.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <stdexcept>

namespace slime {
namespace {

double besselJ(int n, double x) { return std::sph_bessel(static_cast<unsigned>(n), x); }

// j_n'(x) = (n/x) j_n(x) − j_(n+1)(x).
double besselJPrime(int n, double x) { return n / x * besselJ(n, x) - besselJ(n + 1, x); }

double waveSpeedRatio(double poisson) { return std::sqrt(2.0 * (1.0 - poisson) / (1.0 - 2.0 * poisson)); }

struct Radial {
  double f, f1, f2;  // j_n(αρ) and its first two derivatives in ρ
  double g, g1;      // j_n(βρ) and its first derivative in ρ
};

Radial radialFunctions(int n, double rho, double alpha, double beta) {
  Radial r;
  r.f = besselJ(n, alpha * rho);
  r.f1 = alpha * besselJPrime(n, alpha * rho);
  // Bessel's equation: f'' = −(2/ρ) f' − (α² − n(n+1)/ρ²) f.
  r.f2 = -2.0 / rho * r.f1 - (alpha * alpha - n * (n + 1) / (rho * rho)) * r.f;
  r.g = besselJ(n, beta * rho);
  r.g1 = beta * besselJPrime(n, beta * rho);
  return r;
}

}  // namespace

double torsionalCharacteristic(int degree, double eta) {
  return (degree - 1) * besselJ(degree, eta) - eta * besselJ(degree + 1, eta);
}

double spheroidalDeterminant(int degree, double eta, double poisson) {
  const int n = degree;
  const double lambda = 2.0 * poisson / (1.0 - 2.0 * poisson);  // with μ = 1
  const double beta = eta, alpha = eta / waveSpeedRatio(poisson);
  const Radial r = radialFunctions(n, 1.0, alpha, beta);
  const double nn = n * (n + 1.0);
  // Rows: σ_rr and σ_rθ at ρ = 1 (over μ); columns: the A (∇φ) and B (∇×∇×xψ) parts.
  const double normalA = -lambda * alpha * alpha * r.f + 2.0 * r.f2;
  const double normalB = 2.0 * nn * (r.g1 - r.g);
  const double shearA = 2.0 * (r.f1 - r.f);
  const double shearB = -2.0 * r.g1 - beta * beta * r.g + (2.0 * nn - 2.0) * r.g;
  return normalA * shearB - normalB * shearA;
}

double lambRoot(int degree, bool spheroidal, double poisson, double from) {
  const auto value = [&](double eta) {
    return spheroidal ? spheroidalDeterminant(degree, eta, poisson) : torsionalCharacteristic(degree, eta);
  };
  constexpr double kScan = 0.01;
  double low = from, valueLow = value(low);
  for (double high = from + kScan; high < from + 50.0; high += kScan) {
    const double valueHigh = value(high);
    if ((valueLow < 0.0) != (valueHigh < 0.0)) {
      double a = low, b = high;
      for (int i = 0; i < 100; ++i) {
        const double middle = 0.5 * (a + b);
        if ((value(middle) < 0.0) == (value(a) < 0.0)) a = middle;
        else b = middle;
      }
      return 0.5 * (a + b);
    }
    low = high;
    valueLow = valueHigh;
  }
  throw std::runtime_error("no Lamb root found");
}

glm::dvec3 torsionalModeShape(const glm::dvec3& x, double radius, double eta) {
  // u_φ ∝ j_2(ηr/R) ∂Y/∂θ with Y = P_2(cos θ): j_2(ηr/R) (z/r) (−y, x, 0)/r up to sign.
  const double r = glm::length(x);
  if (r <= 0.0) return glm::dvec3(0.0);
  return besselJ(2, eta * r / radius) * (x.z / r) * glm::dvec3(-x.y, x.x, 0.0) / r;
}

glm::dvec3 spheroidalModeShape(const glm::dvec3& x, double radius, double eta, double poisson) {
  constexpr int n = 2;
  const double beta = eta, alpha = eta / waveSpeedRatio(poisson);
  const double lambda = 2.0 * poisson / (1.0 - 2.0 * poisson);
  const Radial surface = radialFunctions(n, 1.0, alpha, beta);
  // The null vector of the boundary system: (A, B) = (normalB, −normalA).
  const double a = 2.0 * n * (n + 1.0) * (surface.g1 - surface.g);
  const double b = -(-lambda * alpha * alpha * surface.f + 2.0 * surface.f2);
  const double r = glm::length(x);
  const double rho = std::max(r / radius, 1e-9);
  const Radial inside = radialFunctions(n, rho, alpha, beta);
  const double radial = a * inside.f1 + b * n * (n + 1.0) * inside.g / rho;       // U(ρ)
  const double tangential = a * inside.f / rho + b * (inside.g / rho + inside.g1);  // V(ρ)
  if (r <= 0.0) return glm::dvec3(0.0);
  const glm::dvec3 rhat = x / r;
  const double cosTheta = rhat.z, sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
  const double legendre = 0.5 * (3.0 * cosTheta * cosTheta - 1.0);  // Y = P_2(cos θ)
  // ∇_s Y = dY/dθ θ̂ = −3 cos θ sin θ θ̂, θ̂ = (cos θ cos φ, cos θ sin φ, −sin θ).
  glm::dvec3 thetaHat(0.0);
  if (sinTheta > 1e-12) thetaHat = glm::dvec3(cosTheta * rhat.x / sinTheta, cosTheta * rhat.y / sinTheta, -sinTheta);
  return radial * legendre * rhat + tangential * (-3.0 * cosTheta * sinTheta) * thetaHat;
}

}  // namespace slime
