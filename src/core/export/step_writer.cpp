// STEP writer (step_writer.h).
#include "core/export/step_writer.h"

#include <cmath>
#include <ostream>
#include <string>
#include <vector>

namespace polarview {

namespace {

// Entities are numbered as they are written: #1, #2, ... in file order.
class StepEntities {
 public:
  explicit StepEntities(std::ostream& out) : out_(out) {}
  int add(const std::string& record) {
    out_ << '#' << next_ << '=' << record << ";\n";
    return next_++;
  }

 private:
  std::ostream& out_;
  int next_ = 1;
};

std::string ref(int id) { return "#" + std::to_string(id); }

std::string refList(const std::vector<int>& ids) {
  std::string text = "(";
  for (size_t k = 0; k < ids.size(); ++k) text += (k ? "," : "") + ref(ids[k]);
  return text + ")";
}

std::string cartesianPoint(const Point& p) {
  return "CARTESIAN_POINT('',(" + stepReal(p.x) + "," + stepReal(p.y) + "," + stepReal(p.z) + "))";
}

std::string faceName(const CadSurface& surface) {
  std::string name = std::string(patchKindName(surface.kind)) + " level " + std::to_string(surface.level);
  if (surface.ring >= 0) name += " ring " + std::to_string(surface.ring);
  name += " patch " + std::to_string(surface.patch);
  if (surface.pieces > 1) name += " piece " + std::to_string(surface.piece + 1) + "/" + std::to_string(surface.pieces);
  return name;
}

// The entities every face refers to: the 2D context of the pcurves and the four directions of
// the parameter square's sides.
struct SharedEntities {
  int context2d = 0;
  int plusU = 0, minusU = 0, plusV = 0, minusV = 0;  // DIRECTIONs in (u, v)
};

// Writes the unit, product and context entities; returns the 3D context's id.
int writeContext(StepEntities& step, const CadSurfaceSet& set, const CadFileInfo& info) {
  int length = 0;
  switch (info.unit) {
    case CadUnit::Millimetre: length = step.add("(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.))"); break;
    case CadUnit::Metre: length = step.add("(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT($,.METRE.))"); break;
    case CadUnit::Inch: {
      const int mm = step.add("(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.))");
      const int factor = step.add("LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(25.4)," + ref(mm) + ")");
      const int dimensions = step.add("DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.)");
      length = step.add("(CONVERSION_BASED_UNIT('INCH'," + ref(factor) + ")LENGTH_UNIT()NAMED_UNIT(" + ref(dimensions) + "))");
      break;
    }
  }
  const int angle = step.add("(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.))");
  const int solidAngle = step.add("(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT())");
  const double uncertainty = set.boxDiagonal > 0.0 ? 1e-7 * set.boxDiagonal : 1e-7;
  const int accuracy = step.add("UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(" + stepReal(uncertainty) + ")," + ref(length) +
                                ",'distance_accuracy_value','confusion accuracy')");
  return step.add("(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((" + ref(accuracy) +
                  "))GLOBAL_UNIT_ASSIGNED_CONTEXT((" + ref(length) + "," + ref(angle) + "," + ref(solidAngle) +
                  "))REPRESENTATION_CONTEXT('3D','3D context with units and uncertainty'))");
}

// The product structure around the shape representation `representation`.
void writeProduct(StepEntities& step, const CadFileInfo& info, int representation) {
  const int application = step.add("APPLICATION_CONTEXT('core data for automotive mechanical design processes')");
  step.add("APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000," + ref(application) + ")");
  const int productContext = step.add("PRODUCT_CONTEXT(''," + ref(application) + ",'mechanical')");
  const std::string name = stepString(info.productName);
  const int product = step.add("PRODUCT(" + name + "," + name + ",''," + refList({productContext}) + ")");
  step.add("PRODUCT_RELATED_PRODUCT_CATEGORY('part',$," + refList({product}) + ")");
  const int formation = step.add("PRODUCT_DEFINITION_FORMATION('',''," + ref(product) + ")");
  const int definitionContext = step.add("PRODUCT_DEFINITION_CONTEXT('part definition'," + ref(application) + ",'design')");
  const int definition = step.add("PRODUCT_DEFINITION('design',''," + ref(formation) + "," + ref(definitionContext) + ")");
  const int shape = step.add("PRODUCT_DEFINITION_SHAPE('',''," + ref(definition) + ")");
  step.add("SHAPE_DEFINITION_REPRESENTATION(" + ref(shape) + "," + ref(representation) + ")");
}

// The surface of each face: its control points and B_SPLINE_SURFACE_WITH_KNOTS.
struct WrittenSurface {
  int id = 0;
  std::vector<int> points;  // CARTESIAN_POINT ids, cp's order
};

WrittenSurface writeSurface(StepEntities& step, const CadSurface& surface) {
  const BezierPatch& b = surface.bezier;
  const int rows = b.degU + 1, columns = b.degV + 1;
  WrittenSurface out;
  out.points.resize(b.cp.size());
  for (size_t k = 0; k < b.cp.size(); ++k) out.points[k] = step.add(cartesianPoint(b.cp[k]));
  std::string net = "(";
  for (int i = 0; i < rows; ++i) {
    std::vector<int> row(out.points.begin() + columns * i, out.points.begin() + columns * (i + 1));
    net += (i ? "," : "") + refList(row);
  }
  net += ")";
  const std::string knotsU = "(" + std::to_string(rows) + "," + std::to_string(rows) + ")";
  const std::string knotsV = "(" + std::to_string(columns) + "," + std::to_string(columns) + ")";
  out.id = step.add("B_SPLINE_SURFACE_WITH_KNOTS(''," + std::to_string(b.degU) + "," + std::to_string(b.degV) + "," + net +
                    ",.UNSPECIFIED.,.F.,.F.,.F.," + knotsU + "," + knotsV + ",(0.,1.),(0.,1.),.PIECEWISE_BEZIER_KNOTS.)");
  return out;
}

// The ids of side `side`'s control points of a written surface, in the side's direction
// (cadSideCurve's order).
std::vector<int> sidePointIds(const CadSurface& surface, const WrittenSurface& written, int side) {
  const int columns = surface.bezier.degV + 1, degU = surface.bezier.degU, degV = surface.bezier.degV;
  auto point = [&](int i, int j) { return written.points[size_t(columns * i + j)]; };
  std::vector<int> ids;
  switch (side) {
    case 0: for (int i = 0; i <= degU; ++i) ids.push_back(point(i, 0)); break;
    case 1: for (int j = 0; j <= degV; ++j) ids.push_back(point(degU, j)); break;
    case 2: for (int i = degU; i >= 0; --i) ids.push_back(point(i, degV)); break;
    default: for (int j = degV; j >= 0; --j) ids.push_back(point(0, j)); break;
  }
  return ids;
}

// The pcurve of one use of an edge: the line in the face's parameter square that the edge's
// parameter s in [0, 1] runs along (cad_topology.h, SIDES).
int writePcurve(StepEntities& step, const SharedEntities& shared, int surface, const CadCoedge& use) {
  const glm::dvec2 from = cadSideParameter(use.side, use.forward ? use.t0 : use.t1);
  const glm::dvec2 to = cadSideParameter(use.side, use.forward ? use.t1 : use.t0);
  const glm::dvec2 along = to - from;
  const double length = std::abs(along.x) + std::abs(along.y);  // sides are axis-parallel
  const int direction = along.x > 0.0   ? shared.plusU
                        : along.x < 0.0 ? shared.minusU
                        : along.y > 0.0 ? shared.plusV
                                        : shared.minusV;
  const int origin = step.add("CARTESIAN_POINT('',(" + stepReal(from.x) + "," + stepReal(from.y) + "))");
  const int vector = step.add("VECTOR(''," + ref(direction) + "," + stepReal(length) + ")");
  const int line = step.add("LINE(''," + ref(origin) + "," + ref(vector) + ")");
  const int representation =
      step.add("DEFINITIONAL_REPRESENTATION(''," + refList({line}) + "," + ref(shared.context2d) + ")");
  return step.add("PCURVE(''," + ref(surface) + "," + ref(representation) + ")");
}

// Every EDGE_CURVE of the shell: its curve (the first use's side piece), a pcurve per use and its
// vertices. Returns the EDGE_CURVE ids.
std::vector<int> writeEdges(StepEntities& step, const SharedEntities& shared, const CadSurfaceSet& set,
                            const CadTopology& topology, const std::vector<WrittenSurface>& surfaces) {
  std::vector<int> vertices(topology.vertices.size());
  for (size_t v = 0; v < vertices.size(); ++v) {
    const int point = step.add(cartesianPoint(topology.vertices[v]));
    vertices[v] = step.add("VERTEX_POINT(''," + ref(point) + ")");
  }
  // The uses of each edge, as (surface, coedge).
  std::vector<std::vector<std::pair<size_t, CadCoedge>>> uses(topology.edges.size());
  for (size_t s = 0; s < topology.loops.size(); ++s)
    for (const CadCoedge& coedge : topology.loops[s]) uses[size_t(coedge.edge)].push_back({s, coedge});

  std::vector<int> edges(topology.edges.size());
  for (size_t e = 0; e < topology.edges.size(); ++e) {
    const CadEdge& edge = topology.edges[e];
    const CadSurface& surface = set.surfaces[edge.surface];
    std::vector<int> points;
    if (edge.t0 == 0.0 && edge.t1 == 1.0) {
      points = sidePointIds(surface, surfaces[edge.surface], edge.side);
    } else {
      for (const Point& p : bezierSegment(cadSideCurve(surface, edge.side), edge.t0, edge.t1))
        points.push_back(step.add(cartesianPoint(p)));
    }
    const int degree = int(points.size()) - 1;
    const int curve = step.add("B_SPLINE_CURVE_WITH_KNOTS(''," + std::to_string(degree) + "," + refList(points) +
                               ",.UNSPECIFIED.,.F.,.F.,(" + std::to_string(degree + 1) + "," +
                               std::to_string(degree + 1) + "),(0.,1.),.PIECEWISE_BEZIER_KNOTS.)");
    std::vector<int> pcurves;
    for (const auto& [s, use] : uses[e]) pcurves.push_back(writePcurve(step, shared, surfaces[s].id, use));
    const int surfaceCurve = step.add("SURFACE_CURVE(''," + ref(curve) + "," + refList(pcurves) + ",.PCURVE_S1.)");
    edges[e] = step.add("EDGE_CURVE(''," + ref(vertices[size_t(edge.start)]) + "," + ref(vertices[size_t(edge.end)]) +
                        "," + ref(surfaceCurve) + ",.T.)");
  }
  return edges;
}

// One ADVANCED_FACE: its loop of oriented edges (layout in the header); returns its id.
// `reversed`: the face's normal is the surface's turned round (same_sense false), and its loop,
// counter-clockwise about the surface's normal, is used backwards (ISO 10303-42 FACE_BOUND).
int writeFace(StepEntities& step, const CadSurface& surface, int surfaceId, const std::vector<CadCoedge>& loop,
              const std::vector<int>& edges, bool reversed) {
  std::vector<int> oriented;
  for (const CadCoedge& use : loop)
    oriented.push_back(
        step.add("ORIENTED_EDGE('',*,*," + ref(edges[size_t(use.edge)]) + (use.forward ? ",.T.)" : ",.F.)")));
  const int edgeLoop = step.add("EDGE_LOOP(''," + refList(oriented) + ")");
  const int bound = step.add("FACE_OUTER_BOUND(''," + ref(edgeLoop) + (reversed ? ",.F.)" : ",.T.)"));
  return step.add("ADVANCED_FACE(" + stepString(faceName(surface)) + "," + refList({bound}) + "," + ref(surfaceId) +
                  (reversed ? ",.F.)" : ",.T.)"));
}

}  // namespace

std::string stepString(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') out += "''";
    else if (c == '\\') out += "\\\\";
    else if (c >= 32 && c < 127) out += c;
    else out += '_';
  }
  return out + "'";
}

std::string stepReal(double value) { return cadReal(value, 'E'); }

void writeStep(std::ostream& out, const CadSurfaceSet& set, const CadFileInfo& info) {
  writeStep(out, set, cadTopology(set), info);
}

void writeStep(std::ostream& out, const CadSurfaceSet& set, const CadTopology& topology, const CadFileInfo& info) {
  out << "ISO-10303-21;\nHEADER;\n"
      << "FILE_DESCRIPTION((" << stepString(info.description) << "),'2;1');\n"
      << "FILE_NAME(" << stepString(info.fileName) << "," << stepString(info.timestamp)
      << ",('polarview'),(''),'polarview','polarview','');\n"
      << "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n";
  StepEntities step(out);
  const int context3d = writeContext(step, set, info);
  SharedEntities shared;
  shared.context2d = step.add("(GEOMETRIC_REPRESENTATION_CONTEXT(2)PARAMETRIC_REPRESENTATION_CONTEXT()"
                              "REPRESENTATION_CONTEXT('2D SPACE',''))");
  shared.plusU = step.add("DIRECTION('',(1.,0.))");
  shared.minusU = step.add("DIRECTION('',(-1.,0.))");
  shared.plusV = step.add("DIRECTION('',(0.,1.))");
  shared.minusV = step.add("DIRECTION('',(0.,-1.))");

  std::vector<WrittenSurface> surfaces;
  surfaces.reserve(set.surfaces.size());
  for (const CadSurface& surface : set.surfaces) surfaces.push_back(writeSurface(step, surface));
  const std::vector<int> edges = writeEdges(step, shared, set, topology, surfaces);
  std::vector<int> faces;
  faces.reserve(set.surfaces.size());
  for (size_t s = 0; s < set.surfaces.size(); ++s)
    if (!topology.loops[s].empty())  // a surface shrunk to a point bounds nothing
      faces.push_back(writeFace(step, set.surfaces[s], surfaces[s].id, topology.loops[s], edges, topology.inwards));
  // A closed shell bounds a solid; an open one is a surface model.
  const bool closed = topology.closed();
  const int shell = step.add(std::string(closed ? "CLOSED_SHELL" : "OPEN_SHELL") + "(''," + refList(faces) + ")");
  const int model = closed ? step.add("MANIFOLD_SOLID_BREP(" + stepString(info.productName) + "," + ref(shell) + ")")
                           : step.add("SHELL_BASED_SURFACE_MODEL(''," + refList({shell}) + ")");
  const int origin = step.add("CARTESIAN_POINT('',(0.,0.,0.))");
  const int axisZ = step.add("DIRECTION('',(0.,0.,1.))");
  const int axisX = step.add("DIRECTION('',(1.,0.,0.))");
  const int placement = step.add("AXIS2_PLACEMENT_3D(''," + ref(origin) + "," + ref(axisZ) + "," + ref(axisX) + ")");
  const char* kind = closed ? "ADVANCED_BREP_SHAPE_REPRESENTATION(" : "MANIFOLD_SURFACE_SHAPE_REPRESENTATION(";
  const int representation =
      step.add(kind + stepString(info.productName) + "," + refList({placement, model}) + "," + ref(context3d) + ")");
  writeProduct(step, info, representation);
  out << "ENDSEC;\nEND-ISO-10303-21;\n";
}

}  // namespace polarview
