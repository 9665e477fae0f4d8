// The "Poles" panel: the pole inspector's numbers and two plots (ui/viewer_panels.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <imgui.h>

#include "session/command_ids.h"
#include "session/command_table.h"
#include "ui/viewer_panels.h"

namespace polarview {
namespace ids = command_ids;
namespace {

// One line of a plot: its colour and points (x, y); non-finite y are gaps.
struct PlotSeries {
  ImU32 colour;
  std::vector<float> x, y;
};

ImU32 seriesColour(int k) {
  static const ImU32 colours[] = {IM_COL32(90, 170, 255, 255), IM_COL32(255, 150, 60, 255), IM_COL32(120, 220, 120, 255),
                                  IM_COL32(230, 90, 200, 255)};
  return colours[k % 4];
}

// Lines in a box the width of the panel, with the y range written at its corners and `xLabel`
// below. Enough for reading trends (ImGui's PlotLines draws one series without axes).
void drawPlot(const char* id, const std::vector<PlotSeries>& series, const char* xLabel, const char* yFormat, float height) {
  float xMin = INFINITY, xMax = -INFINITY, yMin = INFINITY, yMax = -INFINITY;
  for (const PlotSeries& s : series)
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!std::isfinite(s.y[i])) continue;
      xMin = std::min(xMin, s.x[i]), xMax = std::max(xMax, s.x[i]);
      yMin = std::min(yMin, s.y[i]), yMax = std::max(yMax, s.y[i]);
    }
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const float width = std::max(ImGui::GetContentRegionAvail().x, 100.0f);
  ImGui::InvisibleButton(id, ImVec2(width, height));
  ImDrawList* list = ImGui::GetWindowDrawList();
  list->AddRectFilled(origin, ImVec2(origin.x + width, origin.y + height), IM_COL32(25, 27, 32, 255));
  list->AddRect(origin, ImVec2(origin.x + width, origin.y + height), IM_COL32(90, 90, 100, 255));
  if (!(xMax > xMin)) return;
  if (!(yMax > yMin)) yMin -= 0.5f, yMax += 0.5f;
  const float pad = 4.0f;
  auto at = [&](float x, float y) {
    return ImVec2(origin.x + pad + (x - xMin) / (xMax - xMin) * (width - 2 * pad),
                  origin.y + height - pad - (y - yMin) / (yMax - yMin) * (height - 2 * pad));
  };
  for (const PlotSeries& s : series) {
    std::vector<ImVec2> run;
    auto flush = [&] {
      if (run.size() >= 2) list->AddPolyline(run.data(), int(run.size()), s.colour, 0, 1.5f);
      else if (run.size() == 1) list->AddCircleFilled(run[0], 2.0f, s.colour);
      run.clear();
    };
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (std::isfinite(s.y[i])) run.push_back(at(s.x[i], s.y[i]));
      else flush();
    }
    flush();
  }
  char text[64];
  std::snprintf(text, sizeof text, yFormat, double(yMax));
  list->AddText(ImVec2(origin.x + pad, origin.y + 1), IM_COL32(200, 200, 200, 255), text);
  std::snprintf(text, sizeof text, yFormat, double(yMin));
  list->AddText(ImVec2(origin.x + pad, origin.y + height - ImGui::GetTextLineHeight() - 1), IM_COL32(200, 200, 200, 255), text);
  ImGui::TextDisabled("%s", xLabel);
}

std::string pointText(const Point& p) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.9g, %.9g, %.9g)", p.x, p.y, p.z);
  return text;
}

// Why the vertices that look polar are not poles: per kind, the nearest few with their reasons.
void drawRejectedCandidates(const PoleSurvey& survey) {
  for (const RejectedPoleGroup& group : survey.rejected) {
    ImGui::TextWrapped("%d: %s", group.count, group.words.c_str());
    ImGui::Indent();
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    for (const RejectedPole& candidate : group.nearest)
      ImGui::TextWrapped("vertex %d (valence %d): %s", candidate.vertex, candidate.valence, candidate.reason.c_str());
    if (group.count > int(group.nearest.size())) ImGui::TextWrapped("... %d more", group.count - int(group.nearest.size()));
    ImGui::PopStyleColor();
    ImGui::Unindent();
  }
}

// No pole: why not, and the conversion that makes poles of n-gon caps (a Blender cylinder's).
void drawNoPoles(PanelContext& ui) {
  const PoleSurvey& survey = ui.status.poleInspector.survey;
  ImGui::TextWrapped("The model has no polar configuration.");
  if (survey.rejectedCount > 0) {
    ImGui::TextWrapped("%d %s like a pole (a fan of triangles) but %s not; the nearest first:", survey.rejectedCount,
                       survey.rejectedCount == 1 ? "vertex looks" : "vertices look", survey.rejectedCount == 1 ? "is" : "are");
    drawRejectedCandidates(survey);
  } else {
    ImGui::TextWrapped("No vertex is the centre of a fan of triangles (a pole: an interior vertex whose faces are all "
                       "triangles, its rim 4-valent vertices between quads).");
  }
  if (survey.fanFaces == 0) return;
  ImGui::Separator();
  ImGui::TextWrapped("%d %s 5 or more sides: as triangle fans around their centres (Blender's triangle fan cap fill), "
                     "caps ringed by quads become poles.",
                     survey.fanFaces, survey.fanFaces == 1 ? "face has" : "faces have");
  commandButton(ui.commands, ids::kModelNgonToFan);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("a new vertex at each such face's centroid, the face a fan of triangles around it (Ctrl+Z returns)");
}

}  // namespace

void drawPoleInspectorPanel(PanelContext& ui) {
  PoleInspectorSettings& s = ui.settings.poleInspector;
  const PoleInspectorStatus& shown = ui.status.poleInspector;
  s.open = true;  // the session computes while the section is open
  if (shown.poles.empty()) {
    drawNoPoles(ui);
    return;
  }
  s.pole = std::clamp(s.pole, 0, int(shown.poles.size()) - 1);
  const std::string current = "vertex " + std::to_string(shown.poles[size_t(s.pole)]);
  if (ImGui::BeginCombo("pole", current.c_str())) {
    for (int k = 0; k < int(shown.poles.size()); ++k)
      if (ImGui::Selectable(("vertex " + std::to_string(shown.poles[size_t(k)])).c_str(), k == s.pole)) s.pole = k;
    ImGui::EndCombo();
  }
  if (shown.computing) ImGui::TextDisabled("computing the rings ...");
  if (!shown.error.empty()) ImGui::TextColored(ImVec4(1.0f, 0.5f, 0.4f, 1.0f), "%s", shown.error.c_str());
  if (shown.inspections.empty()) return;

  // Per scheme: K and H at the pole, and what they mean.
  std::string copied;
  for (size_t k = 0; k < shown.inspections.size(); ++k) {
    const PoleInspection& in = shown.inspections[k];
    ImGui::TextColored(ImColor(seriesColour(int(k))).Value, "%s", schemeChoiceLabel(in.scheme));
    ImGui::SameLine();
    if (in.curvatureDefined) ImGui::Text("K %.6g  H %.6g%s", in.K, in.H, in.directional ? " (Taylor)" : "");
    else ImGui::Text("K, H not defined at the pole");
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("%s", in.note.c_str());
    ImGui::PopStyleColor();
    if (in.hasExpansion && copied.empty()) {
      copied = std::string(schemeChoiceLabel(in.scheme)) + " pole at vertex " + std::to_string(in.vertex) +
               " (valence " + std::to_string(in.valence) + ")\nlimit " + pointText(in.limit) + "\nnormal " + pointText(in.normal);
      for (int i = 0; i < 6; ++i) copied += "\np" + std::to_string(i) + " " + pointText(in.p[size_t(i)]);
      if (in.curvatureDefined) copied += "\nK " + std::to_string(in.K) + " H " + std::to_string(in.H);
    }
  }
  if (!copied.empty() && ImGui::TreeNode("limit, normal, expansion (32)")) {
    ImGui::TextUnformatted(copied.c_str());
    if (ImGui::SmallButton("Copy")) ImGui::SetClipboardText(copied.c_str());
    ImGui::TreePop();
  }

  // How K approaches the pole, ring by ring (log scale).
  std::vector<PlotSeries> convergence;
  int deepest = 1;
  for (size_t k = 0; k < shown.inspections.size(); ++k) {
    PlotSeries series{seriesColour(int(k)), {}, {}};
    for (const PoleRingCurves& ring : shown.inspections[k].rings) {
      series.x.push_back(float(ring.m));
      series.y.push_back(ring.deviation > 0.0 ? float(std::log10(ring.deviation)) : NAN);
      deepest = std::max(deepest, ring.m);
    }
    convergence.push_back(std::move(series));
  }
  ImGui::Text("log10 of max |K - K(pole)| (C2) or spread of K");
  drawPlot("##convergence", convergence, "ring m (level) ->", "%.1f", 110.0f);

  // K around the pole on ring m.
  s.ring = std::clamp(s.ring, 1, deepest);
  ImGui::SliderInt("ring m", &s.ring, 1, deepest);
  std::vector<PlotSeries> around;
  for (size_t k = 0; k < shown.inspections.size(); ++k) {
    PlotSeries series{seriesColour(int(k)), {}, {}};
    for (const PoleRingCurves& ring : shown.inspections[k].rings)
      if (ring.m == s.ring)
        for (size_t a = 0; a < ring.kAlongAngle.size(); ++a) {
          series.x.push_back(360.0f * float(a) / float(ring.kAlongAngle.size()));
          series.y.push_back(float(ring.kAlongAngle[a]));
        }
    around.push_back(std::move(series));
  }
  ImGui::Text("K around the pole on ring %d", s.ring);
  drawPlot("##around", around, "angle (degrees) ->", "%.4g", 110.0f);

  // Pole zoom: the views show rings m..m+2 of this pole at the size of the first rings.
  bool zoom = s.zoomRing >= 0;
  if (ImGui::Checkbox("zoom the views to rings m..m+2", &zoom)) s.zoomRing = zoom ? s.ring : -1;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Figs. 8, 9: the rings scaled by 2^m about the pole (in double), so nested rings compare at any "
                      "depth;\nthe colour range is scaled alike (K / 4^m, H / 2^m), so colours keep their values");
  if (zoom) s.zoomRing = s.ring;
}

void drawSpectrumPanel(PanelContext& ui) {
  SpectrumSettings& s = ui.settings.spectrum;
  const SpectrumStatus& shown = ui.status.spectrum;
  s.open = true;
  ImGui::SliderInt("valence n", &s.valence, 5, 24);
  ImGui::TextDisabled("RTS, matrix (13): k, eigenvalue, Fourier block, mode");
  for (int k = 0; k < int(shown.lines.size()); ++k)
    if (ImGui::Selectable(shown.lines[size_t(k)].c_str(), k == s.k)) s.k = k;
  if (shown.linesValence != s.valence) ImGui::TextDisabled("computing ...");
  ImGui::SliderInt("C2PS steps", &s.c2psSteps, 0, 3);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Fig. 1 d-f: the net after that many C2PS steps (valence x 2 each), magnified back by 2 a step\n"
                      "and its heights by 1 / lambda a step: Lemma 5's scaling shows as equal heights");
  commandButton(ui.commands, ids::kModelEigenvector);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("the net (v1, v2, v_k) over the characteristic map; the views draw its eigenspline (Ctrl+Z returns)");
}

}  // namespace polarview
