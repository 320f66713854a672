// The chamfer highlight layer (Wei, Shi, Yong, "Rendering chamfering structures of sharp
// edges", Visual Computer 2014; docs/design.md §2.2): sharp edges drawn as 1-px line primitives
// carrying both face normals, shaded per pixel by integrating Blinn–Phong over the arc of
// normals (shaders/chamfer.frag, table F(φ, n) in a 1024×128 R32F texture) and blended over
// the faces with W = K·r_e/(d·r_max). Also draws the faces of the shaded style (per-pixel
// Blinn–Phong with crease-aware corner normals), since the highlights continue that shading.
//
// Edge finding and corner normals run on the CPU (chamfer_edges.h), lazily: setMesh() only
// copies the arrays, and the work happens at the first draw that needs it, so a renderer that
// never draws highlights never pays for them.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "core/camera.h"
#include "core/mesh.h"
#include "core/render_params.h"
#include "core/result.h"
#include "gl/chamfer_edges.h"
#include "gl/gl_objects.h"

namespace lodline {

/// One end of an edge line as uploaded: 64 bytes.
struct ChamferVertex {
  glm::vec3 position;  ///< model space
  glm::vec3 normal1;   ///< unit normal of the first adjacent face, model space
  glm::vec3 normal2;   ///< unit normal of the second
  glm::vec3 inward1;   ///< unit direction from the edge into the first face, in its plane
  glm::vec3 inward2;   ///< the same for the second face
  float radius;        ///< r_e at this vertex, model units; 0 = ChamferParams::radius
};

class ChamferLayer {
 public:
  /// An empty layer (draws nothing); create() makes a working one.
  ChamferLayer() = default;
  /// Compiles the shaders and uploads the F(φ, m) table; needs a current context.
  static Result<ChamferLayer> create();

  /// The mesh being drawn: `positions` per vertex, `faces` indexing them, `marked` edges
  /// (pairs of vertex indices, e.g. TriMesh::marked_edges) that are always sharp, and an
  /// optional per-vertex radius r_e (`vertex_radius` empty or one value per vertex, model
  /// units; 0 entries fall back to ChamferParams::radius). Copies the arrays.
  void setMesh(std::span<const glm::vec3> positions, std::span<const std::array<uint32_t, 3>> faces,
               std::span<const EdgeKey> marked = {}, std::span<const float> vertex_radius = {});

  /// Draws the faces with Blinn–Phong (the shaded style) into the bound framebuffer, with the
  /// current depth/polygon-offset state, lit from `light_dir_eye` (towards the light, eye
  /// space; normalised here).
  void drawShadedFaces(const Camera& camera, const ChamferParams& params, glm::vec3 light_dir_eye, int width,
                       int height);

  /// Draws the highlights of the edges with a dihedral angle ≥ params.threshold_deg (plus the
  /// marked ones) over the bound framebuffer, which must hold the faces' depth. `shaded_faces`
  /// says the faces were drawn by drawShadedFaces() (ChamferCompose::kReplace needs their
  /// colours; over other faces the alpha blend is used). Leaves depth test LEQUAL, depth
  /// writes off, blending on with the usual alpha blend function.
  /// `background` (RGB) is what a silhouette edge's rounding uncovers (replacement only).
  void draw(const Camera& camera, const ChamferParams& params, glm::vec3 light_dir_eye, int width, int height,
            bool shaded_faces = true, glm::vec3 background = glm::vec3(1.0f));

  /// Edges drawn by the last draw().
  size_t edgesDrawn() const { return edges_drawn_; }
  /// Candidate edges found on the current mesh (after the first draw()).
  const ChamferEdges& edges() const { return edges_; }
  /// The r_e used where no per-vertex radius is given: params.radius, or the auto default
  /// 0.004 × bounding radius of the mesh.
  float effectiveRadius(const ChamferParams& params) const;
  /// K used by draw(): params.k, or the focal length in pixels (perspective; pixels per model
  /// unit for an orthographic camera).
  static float effectiveK(const Camera& camera, const ChamferParams& params, int height);

 private:
  void prepareEdges();
  void prepareFaces(float smooth_angle_deg);

  GlProgram program_, faces_program_;
  GlTexture table_;
  GlVertexArray edge_vao_, face_vao_;
  GlBuffer edge_vertices_, face_positions_, face_normals_;
  std::vector<glm::vec3> positions_;
  std::vector<std::array<uint32_t, 3>> faces_;
  std::vector<EdgeKey> marked_;
  std::vector<float> vertex_radius_;
  float bounding_radius_ = 1.0f;
  bool edges_dirty_ = true, faces_dirty_ = true;
  bool welded_ = false;  // scratch_ holds the welded mesh and adjacency of the current mesh
  float faces_angle_ = -1.0f;  // smoothing angle the face normals were built with
  ChamferEdgeScratch scratch_;
  ChamferEdges edges_;
  std::vector<ChamferVertex> upload_;
  std::vector<glm::vec3> corner_positions_, corner_normals_;
  size_t edges_drawn_ = 0, face_vertex_count_ = 0;
};

}  // namespace lodline
