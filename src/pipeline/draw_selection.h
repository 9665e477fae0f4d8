// Draw selection: which patches a view draws, and how many of a polar ring's sectors go into one
// tessellated primitive (docs/shading.md, "Close-ups: detail per region").
//
// Close to a deep pole most of the surface's patches are far below a pixel: C2PS level 12 has rings
// of up to 49,152 sectors, each a fortieth of a pixel wide at 1e-3 from the pole, and one level
// for the whole view cannot help there (every level's rings are in the picture). So the choice is
// per region:
//  - culling: patches (and groups of sectors) whose bounding box is outside the view frustum are
//    not drawn;
//  - sector groups: the sectors of one ring row (Patch::link, Patch::sector: the patches between two
//    link circles of one level, in angular order) are drawn 2^a at a time as one primitive that
//    evaluates each of them exactly where its vertices fall (shaders/patch.tese): the same limit
//    surface, tessellated by pixels instead of by patches. a is per row and frame, the largest that
//    keeps every visible group's arc (its sectors' outer chords, at its nearest distance) under
//    DrawSelectionSettings::groupScale segments;
//  - circle densities: the two sides of a link circle (the rows on it, or a row and its pole cap)
//    are cut into the same vertices: rho segments per turn, a power of two times the sector counts,
//    from the circle's projected size, so that both sides agree whatever their group sizes (a
//    T-junction between a level's S sectors and the next level's 2S too).
// GL-free: the renderer uploads DrawItems and rowSlots (render/patch_renderer.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "core/spline/patch.h"
#include "pipeline/shading.h"

namespace polarview {

// One primitive to draw: the patch in `slot`, or sectors sector .. sector + 2^groupLog2 - 1 of a row.
struct DrawItem {
  uint32_t slot = 0;         // the (first) patch's slot
  int32_t rowStart = -1;     // the row's first entry in DrawSelection::rowSlots(); -1: a lone patch
  int32_t sector = 0;        // of the first patch, in the row
  int32_t rowSize = 0;       // sectors in the row
  int8_t groupLog2 = 0;
  // Segments of the group's edges u = 0 and u = 1 (whole group): 2^exponent; -1 where the patch's
  // own rule applies (patch.tesc: adaptive, or the T-junction rule).
  int8_t innerExponent = -1, outerExponent = -1;
  // Tessellated vertices it may produce at most (Mesa's draws count them in 16 bits).
  uint32_t vertexBound = 0;
};

struct DrawSelectionStats {
  size_t items = 0;         // primitives drawn
  size_t patches = 0;       // patches they cover
  size_t culled = 0;        // patches outside the frustum
  size_t rows = 0;          // ring rows drawn in sector groups
};

struct DrawSelectionSettings {
  double tessPixels = 12.0;  // target edge length (ShadingParams::tessPixels)
  int maxTessLevel = 64;
  double viewportHeight = 600.0;
  // Sectors are merged while a group's width stays under groupScale * tessPixels: with 2, a group
  // is at most two tessellation segments along its circles, so merging changes the tessellation
  // only where the sectors were each well below a segment. (1 draws twice the primitives for the
  // same picture; 4 moved the default model's RTS outline by 40 pixels against the full draw.)
  double groupScale = 2.0;
};

class DrawSelection {
 public:
  // The rows of a patch set (patch p in slot slotOfPatch[p]) and its bounding boxes; a row
  // whose sectors are not 0..S-1 once each, or whose circles do not meet their neighbours', is
  // drawn patch by patch. [O(patches)]
  void build(const std::vector<Patch>& patches, const std::vector<uint32_t>& slotOfPatch);
  // The items a view draws (culled, grouped), in slot order. [O(items log items + rows)]
  std::vector<DrawItem> select(const ViewParams& view, const DrawSelectionSettings& settings,
                               DrawSelectionStats* stats = nullptr) const;
  // Per row, its slots in sector order (DrawItem::rowStart indexes it).
  const std::vector<int32_t>& rowSlots() const { return rowSlots_; }
  size_t groupedRows() const { return rows_.size(); }
  size_t patchCount() const { return patchCount_; }

 private:
  struct Box {
    glm::dvec3 lo{0.0}, hi{0.0};
    double innerArc = 0.0;  // a row's group: its sectors' chords along their inner circle (0: a cap),
    double arc = 0.0;       // and along their outer circle,
    glm::dvec3 rimLo{0.0}, rimHi{0.0};  // which lies in this box (a cap's rim; a ring's whole box)
  };
  struct Row {
    int pole = -1, level = 0, link = 0;  // link 0: the pole's caps
    bool isCap = false;
    Point polePoint{0.0};  // a cap row's pole (p0)
    double rimRadius = 0.0;  // its rim's distance from the pole
    int32_t start = 0, size = 0;         // in rowSlots_
    int maxGroupLog2 = 0;
    int innerCircle = -1, outerCircle = -1;  // in circles_; -1: not shared with a grouped row
    std::vector<std::vector<Box>> pyramid;  // [a][group]: bounds of sectors g * 2^a ..
  };
  struct Circle {
    int inside = -1, outside = -1;  // rows
  };
  struct Frame;  // one select() call's state (draw_selection.cpp)
  static Box boxOf(const Patch& patch);
  void linkRows(const std::vector<Patch>& patches, const std::vector<std::vector<size_t>>& rowPatches);
  std::vector<Row> rows_;
  std::vector<Circle> circles_;
  std::vector<int32_t> rowSlots_;
  std::vector<Box> loneBoxes_;  // patches not in a grouped row
  std::vector<uint32_t> loneSlots_;
  std::vector<uint8_t> loneHasJump_;  // a T-junction edge (patch.tesc's rule may reach 64)
  size_t patchCount_ = 0;
};

// The bounding box of a patch's positions (a cap's p0 and rim points, widened by its bulge). [O(1)]
void patchBounds(const Patch& patch, glm::dvec3* lo, glm::dvec3* hi);

}  // namespace polarview
