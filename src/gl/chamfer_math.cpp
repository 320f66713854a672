// Chamfer highlight maths (Wei, Shi, Yong 2014; docs/design.md §2.2). See chamfer_math.h; the
// fragment shader shaders/chamfer.frag repeats these steps in GLSL.
#include "gl/chamfer_math.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace lodline {
namespace {

constexpr float kHalfPi = std::numbers::pi_v<float> * 0.5f;
constexpr float kPi = std::numbers::pi_v<float>;

float texel(std::span<const float> table, int i, int j) {
  return table[static_cast<size_t>(j) * kChamferTablePhiSamples + static_cast<size_t>(i)];
}

}  // namespace

double chamferTableExact(double phi, int m) {
  const double s = std::sin(phi), c = std::cos(phi);
  // Even and odd chains of the recurrence.
  double f = (m % 2 == 0) ? phi : s;
  double cpow = (m % 2 == 0) ? c : c * c;  // cos^(k−1) for the next k
  for (int k = (m % 2 == 0) ? 2 : 3; k <= m; k += 2) {
    f = cpow * s / k + (k - 1.0) / k * f;
    cpow *= c * c;
  }
  return f;
}

void buildChamferTable(std::vector<float>& out) {
  out.resize(static_cast<size_t>(kChamferTablePhiSamples) * kChamferTableExponents);
  const double step = std::numbers::pi / 2.0 / (kChamferTablePhiSamples - 1);
  for (int j = 0; j < kChamferTableExponents; ++j)
    for (int i = 0; i < kChamferTablePhiSamples; ++i)
      out[static_cast<size_t>(j) * kChamferTablePhiSamples + i] =
          static_cast<float>(chamferTableExact(i * step, j + 1));
}

float chamferTableLookup(std::span<const float> table, float phi, float m) {
  const float sign = phi < 0.0f ? -1.0f : 1.0f;
  const float x = std::clamp(std::abs(phi), 0.0f, kHalfPi) * ((kChamferTablePhiSamples - 1) / kHalfPi);
  const int i = std::min(static_cast<int>(x), kChamferTablePhiSamples - 2);
  const float fx = x - static_cast<float>(i);
  const float y = std::clamp(m, 1.0f, static_cast<float>(kChamferTableExponents)) - 1.0f;
  const int j = std::min(static_cast<int>(y), kChamferTableExponents - 2);
  const float fy = y - static_cast<float>(j);
  const float a = texel(table, i, j) + fx * (texel(table, i + 1, j) - texel(table, i, j));
  const float b = texel(table, i, j + 1) + fx * (texel(table, i + 1, j + 1) - texel(table, i, j + 1));
  return sign * (a + fy * (b - a));
}

bool makeChamferArc(glm::vec3 n1, glm::vec3 n2, ChamferArc& out) {
  const glm::vec3 c = glm::cross(n1, n2);
  const float s = glm::length(c);
  if (!(s > 1e-6f)) return false;
  out.axis = c / s;
  out.u = n1;
  out.w = glm::cross(out.axis, n1);
  out.beta = std::atan2(s, glm::dot(n1, n2));
  return true;
}

glm::vec3 chamferArcNormal(const ChamferArc& arc, float t) {
  return std::cos(t) * arc.u + std::sin(t) * arc.w;
}

bool clipChamferArc(const ChamferArc& arc, glm::vec3 dir, float& lo, float& hi, float* center) {
  const float cu = glm::dot(arc.u, dir), cw = glm::dot(arc.w, dir);
  if (cu * cu + cw * cw < 1e-12f) return false;
  float c = std::atan2(cw, cu);
  // The window of normals facing `dir` is [c − π/2, c + π/2]; take the copy (mod 2π)
  // nearest the range. The range is shorter than π, so no other copy can overlap it.
  const float mid = 0.5f * (lo + hi);
  if (c - mid > kPi) c -= 2.0f * kPi;
  if (mid - c > kPi) c += 2.0f * kPi;
  lo = std::max(lo, c - kHalfPi);
  hi = std::min(hi, c + kHalfPi);
  if (center) *center = c;
  return lo < hi;
}

float chamferArcIntegral(const ChamferArc& arc, std::span<const float> table, glm::vec3 x,
                         glm::vec3 p, float n, float lo, float hi) {
  float tau = 0.0f;
  if (!clipChamferArc(arc, x, lo, hi, &tau)) return 0.0f;
  const float cu = glm::dot(arc.u, x), cw = glm::dot(arc.w, x);
  const float rho = std::sqrt(cu * cu + cw * cw);
  // Frame of the arc plane around X's projection: N(θ + τ) = cosθ·xp + sinθ·t.
  const glm::vec3 xp = std::cos(tau) * arc.u + std::sin(tau) * arc.w;
  const glm::vec3 t = -std::sin(tau) * arc.u + std::cos(tau) * arc.w;
  const float a = glm::dot(p, xp), b = glm::dot(p, t);  // p·N'(θ) = b·cosθ − a·sinθ
  const float th1 = lo - tau, th2 = hi - tau;           // both in [−π/2, π/2]
  const float m = n + 1.0f;
  // G1 term: ∫cos^(n+1) from the table; a range straddling θ = 0 (the arc crossing X's
  // projection) is handled by F being odd.
  const float i1 = chamferTableLookup(table, th2, m) - chamferTableLookup(table, th1, m);
  // G2 term, closed form: ∫cos^n·sin = [−cos^(n+1)/(n+1)].
  const float i2 = (std::pow(std::max(std::cos(th1), 0.0f), m) -
                    std::pow(std::max(std::cos(th2), 0.0f), m)) / m;
  return std::pow(rho, n) * (b * i1 - a * i2);
}

glm::vec3 blinnPhong(glm::vec3 normal, glm::vec3 view_dir, glm::vec3 light_dir,
                     const ChamferMaterial& m) {
  const glm::vec3 h = glm::normalize(light_dir + view_dir);
  const float nl = std::max(glm::dot(normal, light_dir), 0.0f);
  const float nh = std::max(glm::dot(normal, h), 0.0f);
  return m.ambient + m.diffuse * nl + m.specular * std::pow(nh, m.shininess);
}

ChamferShade chamferShade(std::span<const float> table, glm::vec3 n1, glm::vec3 n2,
                          glm::vec3 view_dir, glm::vec3 light_dir, const ChamferMaterial& m) {
  ChamferShade out;
  ChamferArc arc;
  if (!makeChamferArc(n1, n2, arc)) return out;
  // Only the part of the strip facing the eye is seen.
  float lo = 0.0f, hi = arc.beta;
  if (!clipChamferArc(arc, view_dir, lo, hi)) return out;
  const glm::vec3 pc = glm::cross(view_dir, arc.axis);
  const float pl = glm::length(pc);
  if (!(pl > 1e-6f)) return out;  // looking along the edge
  const glm::vec3 p = pc / pl;
  const float width = glm::dot(p, chamferArcNormal(arc, hi) - chamferArcNormal(arc, lo));
  if (!(std::abs(width) > 1e-7f)) return out;
  const glm::vec3 h = glm::normalize(light_dir + view_dir);
  const float diffuse = chamferArcIntegral(arc, table, light_dir, p, 1.0f, lo, hi) / width;
  const float specular = chamferArcIntegral(arc, table, h, p, m.shininess, lo, hi) / width;
  out.color = m.ambient + m.diffuse * diffuse + m.specular * specular;
  out.width = std::abs(width);
  return out;
}

float chamferWeight(float k, float radius, float depth, float width) {
  if (!(depth > 0.0f)) return 0.0f;
  return std::clamp(k * radius * width / depth, 0.0f, 1.0f);
}

}  // namespace lodline
