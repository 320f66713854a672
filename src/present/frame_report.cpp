#include "present/frame_report.h"

#include "lines/strokes.h"

namespace lodline {
namespace {

void addLod(LodReport& sum, const LodReport& o) {
  sum.active_vertices += o.active_vertices;
  sum.active_faces += o.active_faces;
  sum.splits += o.splits;
  sum.collapses += o.collapses;
  sum.morphing += o.morphing;
  sum.folded_faces += o.folded_faces;
  // Weighted by visible faces until divided at the end.
  sum.band_fraction += o.band_fraction * static_cast<double>(o.visible_faces);
  sum.band_or_limit_fraction += o.band_or_limit_fraction * static_cast<double>(o.visible_faces);
  sum.visible_faces += o.visible_faces;
}

nlohmann::json kindsJson(const std::array<uint64_t, kLineKindCount>& counts) {
  nlohmann::json j;
  for (int k = 0; k < kLineKindCount; ++k) j[lineKindName(static_cast<LineKind>(k))] = counts[k];
  return j;
}

nlohmann::json lodJson(const LodReport& l) {
  return {{"active_vertices", l.active_vertices}, {"active_faces", l.active_faces},
          {"visible_faces", l.visible_faces},     {"splits", l.splits},
          {"collapses", l.collapses},             {"morphing", l.morphing},
          {"band_fraction", l.band_fraction},     {"band_or_limit_fraction", l.band_or_limit_fraction},
          {"target_area", l.target_area},         {"folded_faces", l.folded_faces}};
}

nlohmann::json clusterJson(const ClusterStats& c) {
  return {{"faces", c.faces},
          {"representatives", c.representatives},
          {"absorbed", c.absorbed},
          {"culled_vertices", c.culled_vertices},
          {"culled_faces", c.culled_faces},
          {"collapsed_faces", c.collapsed_faces},
          {"duplicate_faces", c.duplicate_faces}};
}

}  // namespace

FrameReport reportFrame(const SceneDrawing& scene, ScenePresenter& presenter, LineMask* image_mask) {
  FrameReport r;
  const Camera& camera = presenter.camera();
  const FrameParams& frame = presenter.frame();
  const DepthImage& depth = presenter.depth();
  const std::vector<StrokeRuns>& visible = presenter.visible();
  LineMask mask;
  ObjectReport& t = r.total;
  t.name = "total";
  LodReport lod_sum;
  bool any_lod = false;
  for (size_t i = 0; i < scene.size(); ++i) {
    const SceneDrawing::Object& obj = scene[i];
    const LineDrawing& d = obj.drawing->drawing();
    ObjectReport o;
    o.name = obj.name;
    o.input_vertices = obj.input_vertices;
    o.input_faces = obj.input_faces;
    o.detail_factor = obj.detail_factor;
    o.style = obj.style.style;
    o.active_faces = d.mesh().faceCount();
    o.faces_drawn = presenter.facesDrawn(i);
    o.line_segments = presenter.segmentsDrawn(i);
    const auto vis_segments = countVisibleSegments(d.segments(), camera, depth);
    const auto vis_intersections = countVisibleSegments(obj.intersections, camera, depth);
    for (int k = 0; k < kLineKindCount; ++k) {
      o.lines[k] = obj.style.lines.kinds[k].enabled ? vis_segments[k] + vis_intersections[k] : 0;
      o.lines_extracted[k] = d.segments().counts[k];
    }
    const auto& ix = obj.intersections;
    o.lines_extracted[static_cast<int>(LineKind::kIntersection)] =
        ix.strokeCount() ? ix.points.size() - ix.strokeCount() : 0;
    o.strokes_extracted = d.strokes().strokeCount();
    o.strokes = visible[i].strokeCount();
    o.specks = countSpecks(visible[i].length_px);
    for (size_t s = 0; s < visible[i].strokeCount(); ++s)
      if (visible[i].length_px[s] < kSpeckLengthPx) ++o.specks_by_kind[static_cast<int>(visible[i].kinds[s])];
    rasterizeStrokes(visible[i], frame.width, frame.height, mask);
    o.line_pixels = mask.count();
    rasterizeStrokes(presenter.hidden()[i], frame.width, frame.height, mask);
    o.hidden_line_pixels = mask.count();
    o.outline_fill_px = presenter.outlineFill()[i];
    if (const AdaptiveMesh* lod = obj.drawing->lod()) {
      const LodStats& ls = lod->stats();
      LodReport l;
      float band = 0.0f, band_or_limit = 0.0f;
      uint32_t visible_faces = 0;
      lod->measureBand(band, visible_faces, &band_or_limit);
      l.active_vertices = lod->activeVertexCount();
      l.active_faces = lod->activeFaceCount();
      l.visible_faces = visible_faces;
      l.splits = ls.splits;
      l.collapses = ls.collapses;
      l.morphing = ls.morphing;
      l.band_fraction = band;
      l.band_or_limit_fraction = band_or_limit;
      l.target_area = ls.target_area;
      l.folded_faces = ls.folded_faces;
      addLod(lod_sum, l);
      o.lod = l;
      any_lod = true;
    }
    if (const VertexClustering* vc = obj.drawing->clustering()) o.cluster = vc->stats();
    t.input_vertices += o.input_vertices;
    t.input_faces += o.input_faces;
    t.active_faces += o.active_faces;
    t.faces_drawn += o.faces_drawn;
    t.line_segments += o.line_segments;
    for (int k = 0; k < kLineKindCount; ++k) {
      t.lines[k] += o.lines[k];
      t.lines_extracted[k] += o.lines_extracted[k];
      t.specks_by_kind[k] += o.specks_by_kind[k];
    }
    t.strokes_extracted += o.strokes_extracted;
    t.strokes += o.strokes;
    t.specks += o.specks;
    t.outline_fill_px += o.outline_fill_px;
    r.objects.push_back(std::move(o));
  }
  if (any_lod) {
    if (lod_sum.visible_faces) {
      lod_sum.band_fraction /= static_cast<double>(lod_sum.visible_faces);
      lod_sum.band_or_limit_fraction /= static_cast<double>(lod_sum.visible_faces);
    }
    t.lod = lod_sum;
  }
  if (scene.size() == 1) t.cluster = r.objects[0].cluster;
  // Line pixels of the whole image count a pixel two objects share once.
  rasterizeStrokes(presenter.hiddenAll(), frame.width, frame.height, mask);
  t.hidden_line_pixels = mask.count();
  LineMask& all = image_mask ? *image_mask : mask;
  rasterizeStrokes(presenter.visibleAll(), frame.width, frame.height, all);
  t.line_pixels = all.count();
  r.outline = measureOutlineCoverage(depth, all);

  const CpuTimings cpu = scene.timings();
  r.ms.adapt = scene.adaptMs();
  r.ms.shape = cpu.shape;
  r.ms.view = cpu.view;
  r.ms.extract = cpu.extract;
  r.ms.chain = cpu.chain;
  const PresentTimes& pt = presenter.times();
  r.ms.upload = pt.upload;
  r.ms.render = pt.render;
  r.ms.readback = pt.readback;
  r.ms.visibility = pt.visibility;
  r.ms.strokes = pt.strokes;
  r.texture_drift = presenter.textureDrift();
  return r;
}

nlohmann::json frameStatsJson(const FrameReport& report) {
  const ObjectReport& t = report.total;
  nlohmann::json j;
  j["faces_drawn"] = t.faces_drawn;
  j["line_segments"] = t.line_segments;
  j["lines"] = kindsJson(t.lines);
  j["lines_extracted"] = kindsJson(t.lines_extracted);
  j["strokes"] = t.strokes;
  j["strokes_extracted"] = t.strokes_extracted;
  j["specks"] = t.specks;
  j["specks_by_kind"] = kindsJson(t.specks_by_kind);
  j["line_pixels"] = t.line_pixels;
  j["hidden_line_pixels"] = t.hidden_line_pixels;
  j["outline_fill_px"] = t.outline_fill_px;
  j["active_faces"] = t.active_faces;
  j["outline"] = {{"pixels", report.outline.outline_px},
                  {"covered", report.outline.covered_px},
                  {"coverage", report.outline.coverage()},
                  {"gaps", report.outline.gaps},
                  {"largest_gap_px", report.outline.largest_gap_px}};
  if (t.lod) j["lod"] = lodJson(*t.lod);
  if (t.cluster) j["cluster"] = clusterJson(*t.cluster);
  nlohmann::json objects = nlohmann::json::array();
  for (const ObjectReport& o : report.objects) {
    nlohmann::json oj = {{"name", o.name},
                         {"vertices", o.input_vertices},
                         {"faces", o.input_faces},
                         {"detail_factor", o.detail_factor},
                         {"style", styleName(o.style)},
                         {"faces_drawn", o.faces_drawn},
                         {"line_segments", o.line_segments},
                         {"lines", kindsJson(o.lines)},
                         {"lines_extracted", kindsJson(o.lines_extracted)},
                         {"strokes", o.strokes},
                         {"strokes_extracted", o.strokes_extracted},
                         {"specks", o.specks},
                         {"specks_by_kind", kindsJson(o.specks_by_kind)},
                         {"line_pixels", o.line_pixels},
                         {"hidden_line_pixels", o.hidden_line_pixels},
                         {"outline_fill_px", o.outline_fill_px},
                         {"active_faces", o.active_faces}};
    if (o.lod) oj["lod"] = lodJson(*o.lod);
    if (o.cluster) oj["cluster"] = clusterJson(*o.cluster);
    objects.push_back(oj);
  }
  j["objects"] = objects;
  return j;
}

std::string metricsCsvHeader() {
  return "frame,line_pixels,appeared,vanished,churn,dropped,appeared_raw,vanished_raw,churn_raw,strokes,specks,"
         "active_faces,splits,collapses,ms_total,texture_drift,churn_binary,band_fraction,popped_near_ops,"
         "popped_near_morphs,lines_near_ops,lines_near_morphs\n";
}

void writeMetricsRow(std::ostream& out, int64_t frame, const FrameReport& report, const FrameCoherence& c,
                     double ms_total) {
  const ObjectReport& t = report.total;
  const uint64_t splits = t.lod ? t.lod->splits : 0, collapses = t.lod ? t.lod->collapses : 0;
  out << frame << ',' << c.compensated.line_pixels << ',' << c.compensated.appeared << ',' << c.compensated.vanished
      << ',' << c.compensated.churn() << ',' << c.compensated.dropped << ',' << c.raw.appeared << ','
      << c.raw.vanished << ',' << c.raw.churn() << ',' << t.strokes << ',' << t.specks << ',' << t.active_faces << ','
      << splits << ',' << collapses << ',' << ms_total << ',' << report.texture_drift << ','
      << c.compensated.churnBinary() << ',' << (t.lod ? t.lod->band_fraction : 1.0) << ','
      << c.compensated.popped_near_ops << ',' << c.compensated.popped_near_morphs << ','
      << c.compensated.lines_near_ops << ',' << c.compensated.lines_near_morphs << '\n';
}

}  // namespace lodline
