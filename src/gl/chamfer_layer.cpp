// Chamfer highlight layer (Wei, Shi, Yong 2014; docs/design.md §2.2). See chamfer_layer.h.
#include "gl/chamfer_layer.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/trigonometric.hpp>

#include "gl/chamfer_math.h"
#include "gl/shader.h"

namespace lodline {
namespace {

/// Candidate edges kept on the GPU: everything from this angle up, so that changing the
/// threshold only changes how many are drawn.
constexpr float kMinCandidateAngleDeg = 1.0f;
/// Auto radius, relative to the bounding radius.
constexpr float kAutoRadiusFraction = 0.004f;

void setMaterial(GLuint program, const ChamferParams& p, glm::vec3 light_dir_eye, const Camera& camera,
                 float aspect) {
  glUniformMatrix4fv(glGetUniformLocation(program, "u_view"), 1, GL_FALSE,
                     glm::value_ptr(camera.view()));
  glUniformMatrix4fv(glGetUniformLocation(program, "u_projection"), 1, GL_FALSE,
                     glm::value_ptr(camera.projection(aspect)));
  const glm::vec3 l = glm::normalize(light_dir_eye);
  glUniform3fv(glGetUniformLocation(program, "u_light_eye"), 1, glm::value_ptr(l));
  glUniform3fv(glGetUniformLocation(program, "u_ambient"), 1, glm::value_ptr(p.ambient));
  glUniform3fv(glGetUniformLocation(program, "u_diffuse"), 1, glm::value_ptr(p.diffuse));
  glUniform3fv(glGetUniformLocation(program, "u_specular"), 1, glm::value_ptr(p.specular));
  glUniform1f(glGetUniformLocation(program, "u_shininess"),
              std::clamp(p.shininess, 1.0f, kChamferMaxShininess));
  glUniform1i(glGetUniformLocation(program, "u_orthographic"), camera.orthographic ? 1 : 0);
}

}  // namespace

Result<ChamferLayer> ChamferLayer::create() {
  ChamferLayer c;
  auto program = loadProgram("chamfer.vert", "chamfer.frag");
  if (!program) return program.error();
  auto faces = loadProgram("mesh.vert", "chamfer_faces.frag");
  if (!faces) return faces.error();
  c.program_ = std::move(program.value());
  c.faces_program_ = std::move(faces.value());

  std::vector<float> table;
  buildChamferTable(table);
  c.table_ = makeTexture();
  glBindTexture(GL_TEXTURE_2D, c.table_.id());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, kChamferTablePhiSamples, kChamferTableExponents, 0,
               GL_RED, GL_FLOAT, table.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, 0);

  c.edge_vao_ = makeVertexArray();
  c.edge_vertices_ = makeBuffer();
  glBindVertexArray(c.edge_vao_.id());
  glBindBuffer(GL_ARRAY_BUFFER, c.edge_vertices_.id());
  const GLsizei stride = sizeof(ChamferVertex);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<const void*>(offsetof(ChamferVertex, position)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<const void*>(offsetof(ChamferVertex, normal1)));
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<const void*>(offsetof(ChamferVertex, normal2)));
  glEnableVertexAttribArray(3);
  glVertexAttribPointer(3, 1, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<const void*>(offsetof(ChamferVertex, radius)));
  glEnableVertexAttribArray(4);
  glVertexAttribPointer(4, 3, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<const void*>(offsetof(ChamferVertex, inward1)));
  glEnableVertexAttribArray(5);
  glVertexAttribPointer(5, 3, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<const void*>(offsetof(ChamferVertex, inward2)));

  c.face_vao_ = makeVertexArray();
  c.face_positions_ = makeBuffer();
  c.face_normals_ = makeBuffer();
  glBindVertexArray(c.face_vao_.id());
  glBindBuffer(GL_ARRAY_BUFFER, c.face_positions_.id());
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, c.face_normals_.id());
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
  glBindVertexArray(0);
  return c;
}

void ChamferLayer::setMesh(std::span<const glm::vec3> positions,
                           std::span<const std::array<uint32_t, 3>> faces,
                           std::span<const EdgeKey> marked, std::span<const float> vertex_radius) {
  positions_.assign(positions.begin(), positions.end());
  faces_.assign(faces.begin(), faces.end());
  marked_.assign(marked.begin(), marked.end());
  if (vertex_radius.size() == positions.size())
    vertex_radius_.assign(vertex_radius.begin(), vertex_radius.end());
  else
    vertex_radius_.clear();
  const Bounds b = computeBounds(positions);
  bounding_radius_ = b.radius > 0.0f ? b.radius : 1.0f;
  edges_dirty_ = true;
  faces_dirty_ = true;
  welded_ = false;
}

float ChamferLayer::effectiveRadius(const ChamferParams& params) const {
  return params.radius > 0.0f ? params.radius : kAutoRadiusFraction * bounding_radius_;
}

float ChamferLayer::effectiveK(const Camera& camera, const ChamferParams& params, int height) {
  if (params.k > 0.0f) return params.k;
  if (camera.orthographic) return static_cast<float>(height) / camera.ortho_height;
  return 0.5f * static_cast<float>(height) / std::tan(0.5f * glm::radians(camera.fov_deg));
}

void ChamferLayer::prepareEdges() {
  if (!edges_dirty_) return;
  if (!welded_) prepareChamferMesh(positions_, faces_, scratch_);
  welded_ = true;
  findChamferEdges(positions_, faces_, marked_, kMinCandidateAngleDeg, scratch_, edges_, true);
  upload_.resize(2 * edges_.size());
  for (size_t e = 0; e < edges_.size(); ++e)
    for (int j = 0; j < 2; ++j) {
      const uint32_t v = edges_.vertices[e][j];
      upload_[2 * e + j] = {positions_[v], edges_.normal1[e], edges_.normal2[e],
                            edges_.inward1[e], edges_.inward2[e],
                            vertex_radius_.empty() ? 0.0f : vertex_radius_[v]};
    }
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, edge_vertices_.id());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(upload_.size() * sizeof(ChamferVertex)),
               upload_.data(), GL_DYNAMIC_DRAW);
  edges_dirty_ = false;
}

void ChamferLayer::prepareFaces(float smooth_angle_deg) {
  if (!faces_dirty_ && smooth_angle_deg == faces_angle_) return;
  if (!welded_) prepareChamferMesh(positions_, faces_, scratch_);
  welded_ = true;
  computeCornerNormals(positions_, faces_, smooth_angle_deg, scratch_, corner_normals_, true);
  corner_positions_.resize(3 * faces_.size());
  const uint32_t nv = static_cast<uint32_t>(positions_.size());
  for (size_t f = 0; f < faces_.size(); ++f)
    for (int j = 0; j < 3; ++j)
      corner_positions_[3 * f + j] = faces_[f][j] < nv ? positions_[faces_[f][j]] : glm::vec3(0.0f);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, face_positions_.id());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(corner_positions_.size() * sizeof(glm::vec3)),
               corner_positions_.data(), GL_DYNAMIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, face_normals_.id());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(corner_normals_.size() * sizeof(glm::vec3)),
               corner_normals_.data(), GL_DYNAMIC_DRAW);
  face_vertex_count_ = corner_positions_.size();
  faces_angle_ = smooth_angle_deg;
  faces_dirty_ = false;
}

void ChamferLayer::drawShadedFaces(const Camera& camera, const ChamferParams& params, glm::vec3 light_dir_eye,
                                   int width, int height) {
  if (!faces_program_) return;
  prepareFaces(params.threshold_deg);
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  glUseProgram(faces_program_.id());
  setMaterial(faces_program_.id(), params, light_dir_eye, camera, aspect);
  glBindVertexArray(face_vao_.id());
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(face_vertex_count_));
  glBindVertexArray(0);
}

void ChamferLayer::draw(const Camera& camera, const ChamferParams& params, glm::vec3 light_dir_eye, int width,
                        int height, bool shaded_faces, glm::vec3 background) {
  edges_drawn_ = 0;
  if (!program_) return;
  prepareEdges();
  const size_t count = edges_.countAtLeast(std::max(params.threshold_deg, kMinCandidateAngleDeg));
  if (count == 0) return;
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glLineWidth(1.0f);
  glUseProgram(program_.id());
  setMaterial(program_.id(), params, light_dir_eye, camera, aspect);
  glUniform1f(glGetUniformLocation(program_.id(), "u_radius"), effectiveRadius(params));
  glUniform1f(glGetUniformLocation(program_.id(), "u_k"), effectiveK(camera, params, height));
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, table_.id());
  glUniform1i(glGetUniformLocation(program_.id(), "u_table"), 0);
  glBindVertexArray(edge_vao_.id());
  const GLint compose_loc = glGetUniformLocation(program_.id(), "u_compose");
  const GLint sign_loc = glGetUniformLocation(program_.id(), "u_sign");
  if (params.compose == ChamferCompose::kReplace && shaded_faces) {
    // Signed change Δ in two additive passes (fixed-point targets clamp negative outputs).
    // Wide enough for every pixel the strip (≤ 1 px either side of the edge) touches.
    GLfloat range[2] = {1.0f, 1.0f};
    glGetFloatv(GL_ALIASED_LINE_WIDTH_RANGE, range);
    glLineWidth(std::clamp(3.0f, range[0], range[1]));
    glUniform2f(glGetUniformLocation(program_.id(), "u_viewport"), static_cast<float>(width),
                static_cast<float>(height));
    glUniform3fv(glGetUniformLocation(program_.id(), "u_background"), 1,
                 glm::value_ptr(background));
    glUniform1i(compose_loc, 1);
    glBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);
    glUniform1f(sign_loc, 1.0f);
    glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(2 * count));
    glBlendEquation(GL_FUNC_REVERSE_SUBTRACT);
    glUniform1f(sign_loc, -1.0f);
    glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(2 * count));
    glBlendEquation(GL_FUNC_ADD);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glLineWidth(1.0f);
  } else {
    glUniform1i(compose_loc, 0);
    glUniform1f(sign_loc, 1.0f);
    glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(2 * count));
  }
  glBindVertexArray(0);
  edges_drawn_ = count;
}

}  // namespace lodline
