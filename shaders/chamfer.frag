#version 330 core
// Chamfer edge highlights, per pixel (Wei, Shi, Yong, "Rendering chamfering structures of
// sharp edges", Visual Computer 2014; docs/design.md §2.2). The edge is a thin rounded strip whose
// normals sweep the arc N(t) = cos t·u + sin t·w, t ∈ [0, β], from N1 to N2. The pixel shows
// Blinn–Phong averaged over the strip's projected width: ∫ I(N) (P·dN) / ∫ (P·dN), with P ⟂
// to the view direction and the edge axis. For each of the light L (diffuse, n = 1) and the
// half vector H (specular, n = shininess), with θ measured from X's projection on the arc
// plane (length ρ) and A = P·X̂p, B = P·T:
//   ∫ (N·X)^n (P·dN) = ρ^n·[ B·(F(θ2, n+1) − F(θ1, n+1)) − A·(cos^(n+1)θ1 − cos^(n+1)θ2)/(n+1) ]
// F(φ, m) = ∫₀^φ cos^m comes from a 1024×128 table (φ ∈ [0, π/2], m = 1..128) read with
// texelFetch and interpolated linearly here in full float precision; F is odd in φ, which
// covers arcs straddling X̂p. The layer is blended with alpha W = K·r_e/(d·r_max),
// r_max = 1/|P·(N1 − N2)| (the visible part of the arc when one face looks away).
// The CPU reference of every step is src/gl/chamfer_math.cpp.
in vec3 v_position_eye;
flat in vec3 v_normal1_eye;
flat in vec3 v_normal2_eye;
in float v_radius;

uniform sampler2D u_table;   // R32F, width 1024 (φ), height 128 (m = row + 1)
uniform vec3 u_light_eye;    // unit vector towards the light, eye space
uniform vec3 u_ambient;
uniform vec3 u_diffuse;
uniform vec3 u_specular;
uniform float u_shininess;   // Blinn–Phong exponent n, 1..127
uniform float u_radius;      // constant r_e, model units (when the vertex has none)
uniform float u_k;           // K of the weight, pixels
uniform bool u_orthographic; // view direction +Z and d = 1
// Composition: 0 = the paper's alpha blend (colour I, alpha W); 1 = replacement: the strip
// takes the place of the bands of the two faces it rounds off: face i recedes from the edge
// by s_i = K·r_e·tan(β/2)·|P·T_i|/d pixels (T_i from the edge into face i, in its plane), so
// on screen the strip is the band [−s1, s2] across the projected edge, its normal N(t) at
// δ(t) = −s1 + (K·r_e/d)·|P·(N(t) − N1)|. The pixel (a 1-px box across the edge at signed
// distance δ) changes by Δ = (K·r_e/d)·|∫ I (P·dN)| over the sub-arc inside the box (the same
// closed form on [t_a, t_b]) − c1·C1 − c2·C2, c_i the box's overlap with face i's receded
// band, C_i face i's own Blinn–Phong. Drawn as 3-px lines, twice, additively:
// u_sign = +1 adds max(Δ, 0), −1 subtracts max(−Δ, 0).
uniform int u_compose;
uniform float u_sign;
uniform vec2 u_viewport;  // framebuffer size, px (replacement only)
uniform vec3 u_background;  // shows where a silhouette edge's rounding uncovers it
uniform mat4 u_projection;
flat in vec3 v_inward1_eye;
flat in vec3 v_inward2_eye;

out vec4 frag_color;

const float kHalfPi = 1.5707963267948966;
const float kPi = 3.141592653589793;
const int kPhiSamples = 1024;
const int kExponents = 128;

vec3 g_u;  // arc frame: N(t) = cos t·u + sin t·w
vec3 g_w;

// F(φ, m), odd in φ, bilinear in (φ, m).
float tableF(float phi, float m) {
  float sgn = phi < 0.0 ? -1.0 : 1.0;
  float x = clamp(abs(phi), 0.0, kHalfPi) * (float(kPhiSamples - 1) / kHalfPi);
  int i = min(int(x), kPhiSamples - 2);
  float fx = x - float(i);
  float y = clamp(m, 1.0, float(kExponents)) - 1.0;
  int j = min(int(y), kExponents - 2);
  float fy = y - float(j);
  float t00 = texelFetch(u_table, ivec2(i, j), 0).r;
  float t10 = texelFetch(u_table, ivec2(i + 1, j), 0).r;
  float t01 = texelFetch(u_table, ivec2(i, j + 1), 0).r;
  float t11 = texelFetch(u_table, ivec2(i + 1, j + 1), 0).r;
  float a = t00 + fx * (t10 - t00);
  float b = t01 + fx * (t11 - t01);
  return sgn * (a + fy * (b - a));
}

vec3 arcNormal(float t) { return cos(t) * g_u + sin(t) * g_w; }

// The t ∈ [lo, hi] with σ·R·cos(t − φ) = y (see main).
float invertG(float y, float sigma, float R, float phi, float lo, float hi) {
  float t = phi - sigma * acos(clamp(sigma * y / R, -1.0, 1.0));
  float mid = 0.5 * (lo + hi);
  t += 2.0 * kPi * floor((mid - t) / (2.0 * kPi) + 0.5);
  return clamp(t, lo, hi);
}

vec2 toScreen(vec3 position_eye) {
  vec4 c = u_projection * vec4(position_eye, 1.0);
  return (c.xy / c.w * 0.5 + 0.5) * u_viewport;
}

vec3 blinnPhong(vec3 n, vec3 view, vec3 h) {
  float nl = max(dot(n, u_light_eye), 0.0);
  float nh = max(dot(n, h), 0.0);
  return clamp(u_ambient + u_diffuse * nl + u_specular * pow(nh, u_shininess), 0.0, 1.0);
}

// Restricts [lo, hi] to the normals facing `dir`; c = dir's arc parameter.
bool clipArc(vec3 dir, inout float lo, inout float hi, out float c) {
  float cu = dot(g_u, dir), cw = dot(g_w, dir);
  c = 0.0;
  if (cu * cu + cw * cw < 1e-12) return false;
  c = atan(cw, cu);
  float mid = 0.5 * (lo + hi);
  if (c - mid > kPi) c -= 2.0 * kPi;
  if (mid - c > kPi) c += 2.0 * kPi;
  lo = max(lo, c - kHalfPi);
  hi = min(hi, c + kHalfPi);
  return lo < hi;
}

// ∫_lo^hi max(N·x, 0)^n (p·N') dt, the paper's closed form.
float arcIntegral(vec3 x, vec3 p, float n, float lo, float hi) {
  float tau;
  if (!clipArc(x, lo, hi, tau)) return 0.0;
  float cu = dot(g_u, x), cw = dot(g_w, x);
  float rho = sqrt(cu * cu + cw * cw);
  vec3 xp = cos(tau) * g_u + sin(tau) * g_w;
  vec3 t = -sin(tau) * g_u + cos(tau) * g_w;
  float a = dot(p, xp), b = dot(p, t);
  float th1 = lo - tau, th2 = hi - tau;
  float m = n + 1.0;
  float i1 = tableF(th2, m) - tableF(th1, m);
  float i2 = (pow(max(cos(th1), 0.0), m) - pow(max(cos(th2), 0.0), m)) / m;
  return pow(rho, n) * (b * i1 - a * i2);
}

void main() {
  vec3 n1 = normalize(v_normal1_eye), n2 = normalize(v_normal2_eye);
  vec3 c = cross(n1, n2);
  float s = length(c);
  if (s < 1e-6) discard;
  vec3 axis = c / s;
  g_u = n1;
  g_w = cross(axis, n1);
  float beta = atan(s, dot(n1, n2));
  vec3 view = u_orthographic ? vec3(0.0, 0.0, 1.0) : normalize(-v_position_eye);
  float lo = 0.0, hi = beta, cv;
  if (!clipArc(view, lo, hi, cv)) discard;  // the strip faces away
  vec3 pc = cross(view, axis);
  float pl = length(pc);
  if (pl < 1e-6) discard;  // looking along the edge
  vec3 p = pc / pl;
  float width = dot(p, arcNormal(hi) - arcNormal(lo));  // = 1/r_max (visible arc)
  float depth = u_orthographic ? 1.0 : -v_position_eye.z;
  float r = v_radius > 0.0 ? v_radius : u_radius;
  float weight = clamp(u_k * r * abs(width) / depth, 0.0, 1.0);
  if (weight < 1.0 / 512.0) discard;  // nothing to add: skip the integrals
  vec3 h = normalize(u_light_eye + view);
  if (u_compose == 0) {
    float diffuse = arcIntegral(u_light_eye, p, 1.0, lo, hi) / width;
    float specular = arcIntegral(h, p, u_shininess, lo, hi) / width;
    vec3 color = clamp(u_ambient + u_diffuse * diffuse + u_specular * specular, 0.0, 1.0);
    frag_color = vec4(color, weight);
    return;
  }
  float kpx = u_k * r / depth;  // pixels per unit of P·N on the strip
  float shrink = kpx * tan(0.5 * beta);
  vec3 t1 = normalize(v_inward1_eye), t2 = normalize(v_inward2_eye);
  bool vis1 = dot(n1, view) > 0.0, vis2 = dot(n2, view) > 0.0;
  float s1 = vis1 ? shrink * abs(dot(p, t1)) : 0.0;
  float s2 = vis2 ? shrink * abs(dot(p, t2)) : 0.0;
  // Screen-space frame of the edge at this fragment: normal pointing into face 2's side.
  float eps = 0.01 * depth;
  vec2 e0 = toScreen(v_position_eye);
  vec2 along = toScreen(v_position_eye + eps * axis) - e0;
  if (dot(along, along) < 1e-12) discard;
  vec2 nrm = normalize(vec2(-along.y, along.x));
  if (dot(toScreen(v_position_eye + eps * t1) - e0, nrm) > 0.0) nrm = -nrm;
  float delta_px = dot(gl_FragCoord.xy - e0, nrm);
  // Strip point of normal N(t) lies at δ(t) = δ_anchor + kpx·(g(t) − g_anchor) across the
  // edge, g(t) = σ·P·N(t) increasing on the visible arc; anchored at a visible face's end.
  float sigma = width > 0.0 ? 1.0 : -1.0;
  float g_lo = sigma * dot(p, arcNormal(lo)), g_hi = sigma * dot(p, arcNormal(hi));
  float d_lo = vis1 ? -s1 : s2 - kpx * (g_hi - g_lo);
  float d_hi = d_lo + kpx * (g_hi - g_lo);
  // The pixel (a 1-px box across the edge) sees the strip over [da, db] ...
  float da = max(delta_px - 0.5, d_lo), db = min(delta_px + 0.5, d_hi);
  // ... and no longer the faces over their receded bands [−s1, 0] and [0, s2].
  float c1 = max(0.0, min(delta_px + 0.5, 0.0) - max(delta_px - 0.5, -s1));
  float c2 = max(0.0, min(delta_px + 0.5, s2) - max(delta_px - 0.5, 0.0));
  if (db <= da && c1 + c2 <= 0.0) discard;  // a pixel of the 3-px line the strip misses
  vec3 strip = vec3(0.0);
  if (db > da) {
    // ... i.e. over the sub-arc [ta, tb]: invert g(t) = σ·R·cos(t − φ), increasing on the
    // visible arc (where σ·sin(t − φ) < 0), so t = φ − σ·acos(σ·y/R) (mod 2π).
    float pa = dot(p, g_u), pb = dot(p, g_w);
    float R = sqrt(pa * pa + pb * pb);
    float phi = atan(pb, pa);
    float ya = g_lo + (da - d_lo) / kpx, yb = g_lo + (db - d_lo) / kpx;
    float ta = invertG(ya, sigma, R, phi, lo, hi), tb = invertG(yb, sigma, R, phi, lo, hi);
    float w_sub = dot(p, arcNormal(tb) - arcNormal(ta));
    float dif = arcIntegral(u_light_eye, p, 1.0, ta, tb);
    float spe = arcIntegral(h, p, u_shininess, ta, tb);
    // Σ colour × projected width over the sub-strip, in pixels (signs follow P·N').
    strip = kpx * sigma * (u_ambient * w_sub + u_diffuse * dif + u_specular * spe);
  }
  // On a silhouette edge the rounded outline lies inside the sharp one: between the strip's
  // end and the sharp edge the background shows instead of the face.
  float gap = 0.0;
  if (!vis2) gap = max(0.0, min(delta_px + 0.5, 0.0) - max(delta_px - 0.5, d_hi));
  if (!vis1) gap = max(0.0, min(delta_px + 0.5, d_lo) - max(delta_px - 0.5, 0.0));
  vec3 delta = strip + gap * u_background - c1 * blinnPhong(n1, view, h) -
               c2 * blinnPhong(n2, view, h);
  frag_color = vec4(max(u_sign * delta, 0.0), 0.0);
}
