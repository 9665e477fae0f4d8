// STEP writer (step_writer.h).
#include "core/export/step_writer.h"

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
  int alongU = 0, alongV = 0;
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

// One side of a face: the B-spline curve through `points` (ids of the surface's control points)
// from vertex `start` to `end`, its pcurve the line from `origin` along `direction` in (u, v).
int writeEdge(StepEntities& step, const SharedEntities& shared, int surface, int degree, const std::vector<int>& points,
              int start, int end, const char* origin, int direction) {
  const int curve = step.add("B_SPLINE_CURVE_WITH_KNOTS(''," + std::to_string(degree) + "," + refList(points) +
                             ",.UNSPECIFIED.,.F.,.F.,(" + std::to_string(degree + 1) + "," + std::to_string(degree + 1) +
                             "),(0.,1.),.PIECEWISE_BEZIER_KNOTS.)");
  const int lineOrigin = step.add(std::string("CARTESIAN_POINT('',") + origin + ")");
  const int vector = step.add("VECTOR(''," + ref(direction) + ",1.)");
  const int line = step.add("LINE(''," + ref(lineOrigin) + "," + ref(vector) + ")");
  const int representation = step.add("DEFINITIONAL_REPRESENTATION(''," + refList({line}) + "," + ref(shared.context2d) + ")");
  const int pcurve = step.add("PCURVE(''," + ref(surface) + "," + ref(representation) + ")");
  const int surfaceCurve = step.add("SURFACE_CURVE(''," + ref(curve) + "," + refList({pcurve}) + ",.PCURVE_S1.)");
  return step.add("EDGE_CURVE(''," + ref(start) + "," + ref(end) + "," + ref(surfaceCurve) + ",.T.)");
}

// One ADVANCED_FACE (layout in the header); returns its id.
int writeFace(StepEntities& step, const SharedEntities& shared, const CadSurface& surface) {
  const BezierPatch& b = surface.bezier;
  const int rows = b.degU + 1, columns = b.degV + 1;
  std::vector<int> points(b.cp.size());
  for (size_t k = 0; k < b.cp.size(); ++k) points[k] = step.add(cartesianPoint(b.cp[k]));
  auto point = [&](int i, int j) { return points[size_t(columns * i + j)]; };
  // The control points of row i (along v) and of column j (along u).
  auto row = [&](int i) {
    std::vector<int> ids;
    for (int j = 0; j < columns; ++j) ids.push_back(point(i, j));
    return ids;
  };
  auto column = [&](int j) {
    std::vector<int> ids;
    for (int i = 0; i < rows; ++i) ids.push_back(point(i, j));
    return ids;
  };

  std::string net = "(";
  for (int i = 0; i < rows; ++i) net += (i ? "," : "") + refList(row(i));
  net += ")";
  const std::string knotsU = "(" + std::to_string(rows) + "," + std::to_string(rows) + ")";
  const std::string knotsV = "(" + std::to_string(columns) + "," + std::to_string(columns) + ")";
  const int id = step.add("B_SPLINE_SURFACE_WITH_KNOTS(''," + std::to_string(b.degU) + "," + std::to_string(b.degV) + "," + net +
                          ",.UNSPECIFIED.,.F.,.F.,.F.," + knotsU + "," + knotsV + ",(0.,1.),(0.,1.),.PIECEWISE_BEZIER_KNOTS.)");

  // Corners (0,0), (1,0), (1,1), (0,1); a cap piece's (0,0) and (0,1) are the one pole vertex.
  const int c00 = step.add("VERTEX_POINT(''," + ref(point(0, 0)) + ")");
  const int c10 = step.add("VERTEX_POINT(''," + ref(point(rows - 1, 0)) + ")");
  const int c11 = step.add("VERTEX_POINT(''," + ref(point(rows - 1, columns - 1)) + ")");
  const int c01 = surface.collapsedAtU0() ? c00 : step.add("VERTEX_POINT(''," + ref(point(0, columns - 1)) + ")");

  std::vector<std::string> loop;
  auto oriented = [&](int edge, bool forward) {
    loop.push_back(ref(step.add("ORIENTED_EDGE('',*,*," + ref(edge) + (forward ? ",.T.)" : ",.F.)"))));
  };
  oriented(writeEdge(step, shared, id, b.degU, column(0), c00, c10, "(0.,0.)", shared.alongU), true);   // v = 0
  oriented(writeEdge(step, shared, id, b.degV, row(rows - 1), c10, c11, "(1.,0.)", shared.alongV), true);   // u = 1
  oriented(writeEdge(step, shared, id, b.degU, column(columns - 1), c01, c11, "(0.,1.)", shared.alongU), false);  // v = 1
  if (!surface.collapsedAtU0())
    oriented(writeEdge(step, shared, id, b.degV, row(0), c00, c01, "(0.,0.)", shared.alongV), false);  // u = 0
  std::string edges = "(";
  for (size_t k = 0; k < loop.size(); ++k) edges += (k ? "," : "") + loop[k];
  const int edgeLoop = step.add("EDGE_LOOP(''," + edges + "))");
  const int bound = step.add("FACE_OUTER_BOUND(''," + ref(edgeLoop) + ",.T.)");
  return step.add("ADVANCED_FACE(" + stepString(faceName(surface)) + "," + refList({bound}) + "," + ref(id) + ",.T.)");
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
  shared.alongU = step.add("DIRECTION('',(1.,0.))");
  shared.alongV = step.add("DIRECTION('',(0.,1.))");

  std::vector<int> faces;
  faces.reserve(set.surfaces.size());
  for (const CadSurface& surface : set.surfaces) faces.push_back(writeFace(step, shared, surface));
  const int shell = step.add("OPEN_SHELL(''," + refList(faces) + ")");
  const int model = step.add("SHELL_BASED_SURFACE_MODEL(''," + refList({shell}) + ")");
  const int origin = step.add("CARTESIAN_POINT('',(0.,0.,0.))");
  const int axisZ = step.add("DIRECTION('',(0.,0.,1.))");
  const int axisX = step.add("DIRECTION('',(1.,0.,0.))");
  const int placement = step.add("AXIS2_PLACEMENT_3D(''," + ref(origin) + "," + ref(axisZ) + "," + ref(axisX) + ")");
  const int representation =
      step.add("MANIFOLD_SURFACE_SHAPE_REPRESENTATION(" + stepString(info.productName) + "," + refList({placement, model}) + "," +
               ref(context3d) + ")");
  writeProduct(step, info, representation);
  out << "ENDSEC;\nEND-ISO-10303-21;\n";
}

}  // namespace polarview
