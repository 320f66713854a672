// GL-free maths of the chamfer edge highlights (Wei, Shi, Yong, "Rendering chamfering
// structures of sharp edges", The Visual Computer 2014; the facts used are summarised in
// docs/design.md §2.2): a sharp edge is treated as a thin rounded strip (a partial cylinder of
// radius r_e) whose normals sweep the arc from the face normal N1 to N2. A pixel on the edge
// shows the Blinn–Phong intensity averaged over the strip's projected width, i.e. integrated
// over the arc with the weight P·dN (P ⟂ to the view direction and to the edge axis):
//
//   ∫ (N·X)^n (P·dN) = ρ^n·[ B·∫cos^(n+1)θ dθ − A·∫cos^nθ sinθ dθ ]   over [θ1, θ2]
//
// where X is the light (diffuse, n = 1) or half vector (specular), ρ = |X projected on the
// arc plane|, θ is measured from that projection, A = P·X̂p and B = P·T (T ⟂ X̂p in the arc
// plane). The sin term is closed form; the cos^(n+1) term comes from the table
// F(φ, m) = ∫₀^φ cos^m θ dθ (1024 φ samples over [0, π/2] × m = 1..128, linear
// interpolation), with F odd-extended to negative φ so arcs straddling X̂p need no special
// case. This file is the CPU reference the fragment shader shaders/chamfer.frag mirrors line
// by line; it includes only glm and std so tests check it without an OpenGL context.
#pragma once

#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace lodline {

/// Table size (as in the paper): φ samples over [0, π/2] (texture width) and exponents m = 1..128
/// (texture height).
inline constexpr int kChamferTablePhiSamples = 1024;
inline constexpr int kChamferTableExponents = 128;
/// The specular term needs F(·, n + 1), so the table supports Blinn–Phong exponents n up to
/// 127 (the diffuse term uses m = 2).
inline constexpr float kChamferMaxShininess = 127.0f;

/// Exact F(φ, m) = ∫₀^φ cos^m θ dθ for φ ∈ [0, π/2], integer m ≥ 0, by the recurrence
/// F(φ,m) = cos^(m−1)φ·sinφ/m + (m−1)/m·F(φ,m−2) from F(φ,0) = φ, F(φ,1) = sinφ (stable:
/// every coefficient is < 1), in double precision.
double chamferTableExact(double phi, int m);

/// Fills `out` (resized to kChamferTablePhiSamples·kChamferTableExponents floats) with
/// F(φ_i, m_j), φ_i = i·(π/2)/1023, m_j = j + 1, row-major by exponent: out[j·1024 + i].
/// This is the layout of the R32F texture (width 1024 = φ, height 128 = m).
void buildChamferTable(std::vector<float>& out);

/// F(φ, m) from `table` (built by buildChamferTable) by bilinear interpolation, φ clamped
/// to [0, π/2] and m to [1, 128]; odd in φ (F(−φ) = −F(φ)). Same arithmetic as the shader.
float chamferTableLookup(std::span<const float> table, float phi, float m);

/// The arc of normals of a rounded edge: N(t) = cos t·u + sin t·w for t ∈ [0, beta], with
/// u = N1, axis = N1×N2/|N1×N2| (the edge direction) and w = axis×u, so N(beta) = N2.
struct ChamferArc {
  glm::vec3 u{0.0f}, w{0.0f}, axis{0.0f};
  float beta = 0.0f;  ///< angle between N1 and N2, radians, in (0, π)
};

/// Builds the arc from unit face normals; false if they are (anti)parallel (no unique arc).
bool makeChamferArc(glm::vec3 n1, glm::vec3 n2, ChamferArc& out);

/// N(t) on the arc.
glm::vec3 chamferArcNormal(const ChamferArc& arc, float t);

/// Restricts [lo, hi] ⊂ [0, beta] to the normals of the hemisphere around `dir`
/// (N(t)·dir ≥ 0). False if nothing remains (or `dir` ∥ axis). `center` receives the arc
/// parameter of dir's projection on the arc plane (shifted within π of the range).
bool clipChamferArc(const ChamferArc& arc, glm::vec3 dir, float& lo, float& hi,
                    float* center = nullptr);

/// ∫_lo^hi max(N(t)·x, 0)^n · (p·N'(t)) dt by the paper's closed form (sin term exact,
/// cos^(n+1) term from `table`); `x` unit, n ∈ [1, 127]. Signed like p·N'.
float chamferArcIntegral(const ChamferArc& arc, std::span<const float> table, glm::vec3 x,
                         glm::vec3 p, float n, float lo, float hi);

/// Blinn–Phong material shared by the shaded faces and the highlights:
/// I = ambient + diffuse·max(N·L, 0) + specular·max(N·H, 0)^shininess.
struct ChamferMaterial {
  glm::vec3 ambient{0.0f};
  glm::vec3 diffuse{0.0f};
  glm::vec3 specular{0.0f};
  float shininess = 32.0f;
};

/// Blinn–Phong of one normal (the faces' shading, and the brute-force reference).
glm::vec3 blinnPhong(glm::vec3 normal, glm::vec3 view_dir, glm::vec3 light_dir,
                     const ChamferMaterial& m);

/// One pixel of the highlight layer.
struct ChamferShade {
  glm::vec3 color{0.0f};  ///< Blinn–Phong averaged over the visible strip (not clamped)
  /// Projected width of the visible strip per unit radius, |P·(N_b − N_a)|; equals the
  /// paper's 1/r_max = |P·(N1 − N2)| when both faces face the viewer; 0 if invisible.
  float width = 0.0f;
};

/// The per-pixel formula: `n1`, `n2` the unit face normals, `view_dir` unit vector from the
/// surface to the eye, `light_dir` unit vector to the light (same space). P = view×axis.
ChamferShade chamferShade(std::span<const float> table, glm::vec3 n1, glm::vec3 n2,
                          glm::vec3 view_dir, glm::vec3 light_dir, const ChamferMaterial& m);

/// Blend weight W = K·r_e/(d·r_max) = K·radius·width/depth clamped to [0, 1] (the paper's
/// blend weight):
/// the fraction of a 1-px line covered by the strip when K is the focal length in pixels.
float chamferWeight(float k, float radius, float depth, float width);

}  // namespace lodline
