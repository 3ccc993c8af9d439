#pragma once
// The struts of a scene as one static mesh, built once per scene (and piece layout and
// colouring) and kept on the GPU: every vertex names the rows of the node table its
// position comes from. Per frame only the node values (displacements) and the element
// values (stresses, moments) change; the magnification, pan and zoom are uniforms, applied in the
// vertex shader (GlRenderer). expand_mesh() evaluates the same formulas on the CPU, for
// figures and for tests without GL.
//
// Node rows are per piece node (a FETI subdomain holds its own copy of an interface node,
// so pieces that do not agree yet are drawn torn apart). A vertex sits at `t` between
// node rows a and b: linear interpolation now; a frame model can make a strut a curve by
// subdividing it into vertices between its two element nodes and interpolating with the
// rotation the node values carry (their third component) - Hermite - in the same place.

#include <array>
#include <cstdint>
#include <vector>

#include "render/draw_list.hpp"
#include "render/mesh_detail.hpp"
#include "render/scene_framing.hpp"
#include "render/view.hpp"
#include "solver/method.hpp"
#include "solver/model.hpp"

namespace fetic::render {

struct MeshVertex {
  std::int32_t node_a = 0, node_b = 0;  // node rows; the vertex sits at t between them
  float t = 0.0f;
  // Screen offsets in pixels along d, the screen direction from node a to node b, and
  // across it (d turned by +90 degrees): across = x * half bar width + y * rim + w * line
  // width, along = z * rim (see MeshUniforms).
  std::array<float, 4> offset{0, 0, 0, 0};
  std::int32_t element = -1;  // row of the element table (value colour); -1: its own colour
  Color color;
};

struct MeshRange {
  std::int32_t first = 0, count = 0;  // vertices, 3 per triangle
};

struct SceneMesh {
  std::uint64_t id = 0;       // unique per build: GlRenderer re-uploads when it changes
  solver::Vec2 origin{0, 0};  // node positions are stored relative to it (float precision)
  // Per node row: reference position (x, y) and gap widening (per unit of m - 1).
  std::vector<std::array<float, 4>> nodes;
  std::vector<MeshVertex> vertices;
  // Drawn in this order: bar rims, bar fills, plane fills, plane mesh lines (only when the
  // elements are large enough on screen), plane piece outlines.
  MeshRange bar_rims, bar_fills, plane_fills, plane_lines, plane_outlines;
  int element_count = 0;
  // The piece layout it was built for (strut, node box per piece), the first node row and
  // element row of each piece.
  std::vector<std::pair<int, solver::NodeBox>> layout;
  std::vector<int> first_node, first_element;
  // Per piece, the elements merged into a cell along and across (1, 1: every element;
  // render/mesh_detail.hpp), and the detail the mesh was built with.
  std::vector<std::array<int, 2>> merged;
  MeshDetail detail;
  ColorBy color_by = ColorBy::Subdomain;
  double smallest_element = 0.0;  // world length of the smallest plane element side

  // True when a snapshot's pieces are the ones this mesh was built for.
  bool fits(const solver::Snapshot& snapshot) const;
};

// The mesh of `model` for the piece layout of `snapshot` (any snapshot of the method),
// every element as it is, or at a level of detail (plane elements below a pixel merged).
SceneMesh build_scene_mesh(const solver::Model& model, const solver::Snapshot& snapshot,
                           const SceneFraming& framing, ColorBy color_by,
                           const MeshDetail& detail = {});

// What changes per frame.
struct MeshValues {
  std::vector<std::array<float, 4>> nodes;  // per node row: ux, uy, rotation, 0
  // Per element row (a merged cell: the mean of its elements), the value over its scale at the
  // element's first node (t = 0) and at its second (t = 1); a vertex at t between them is coloured
  // by the linear blend. Axial stress is constant over an element (both the same); a beam's moment
  // is linear.
  std::vector<std::array<float, 2>> elements;
};
void fill_mesh_values(const SceneMesh& mesh, const solver::Model& model,
                      const solver::Snapshot& snapshot, const SceneFraming& framing,
                      MeshValues& values);

// The uniforms of a draw: world to pixels, magnification, widths.
struct MeshUniforms {
  float magnification = 1.0f;
  float widening = 0.0f;                    // m - 1 when gaps are drawn magnified, else 0
  std::array<float, 2> center{0, 0};        // world point (relative to the mesh origin) ...
  std::array<float, 2> pixel_center{0, 0};  // ... drawn at this pixel
  float pixels_per_unit = 1.0f;
  float half_bar_width = 3.0f;
  float rim = 1.0f;         // 1: bars have a dark rim and pieces are inset at their ends
  float line_width = 1.0f;  // pixels per line-width unit (grows with the text size)
  bool by_value = false;    // colour elements by their values (stress, moment; diverging map)
  bool mesh_lines = true;   // draw plane_lines
};
MeshUniforms mesh_uniforms(const SceneMesh& mesh, const SceneFraming& framing);

// The mesh as triangles of a draw list, exactly as the shader places and colours them.
void expand_mesh(const SceneMesh& mesh, const MeshValues& values, const MeshUniforms& uniforms,
                 DrawList& out);

}  // namespace fetic::render
