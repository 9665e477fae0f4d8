// IGES writer (iges_writer.h).
#include "core/export/iges_writer.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace polarview {

namespace {

constexpr int kSurfaceEntity = 128;

// One section's records: text of at most `width` columns, padded to 72, then the section letter
// and the sequence number.
class IgesSection {
 public:
  IgesSection(std::ostream& out, char letter) : out_(out), letter_(letter) {}
  // Writes one record whose first 72 columns are `text` (padded). [O(1)]
  void record(const std::string& text) {
    // Sequence numbers have 7 columns.
    if (++count_ > 9999999) throw std::runtime_error("IGES output: more than 9999999 records in one section");
    char tail[24];
    std::snprintf(tail, sizeof tail, "%c%7d", letter_, count_);
    out_ << text << std::string(72 - std::min<size_t>(72, text.size()), ' ') << tail << '\n';
  }
  // Writes `parameters` (ending in the record delimiter) in records of `width` columns, breaking
  // after a delimiter where one is near the end, inside a long token otherwise; each record's
  // columns width+1..72 hold `suffix` (right-aligned). Returns the number of records. [O(text)]
  int stream(const std::string& parameters, size_t width, const std::string& suffix) {
    int records = 0;
    for (size_t start = 0; start < parameters.size(); ++records) {
      size_t end = std::min(parameters.size(), start + width);
      if (end < parameters.size()) {
        const size_t delimiter = parameters.find_last_of(",;", end - 1);
        if (delimiter != std::string::npos && delimiter >= start && !insideHollerith(parameters, delimiter)) end = delimiter + 1;
      }
      std::string text = parameters.substr(start, end - start);
      text += std::string(width - text.size(), ' ');
      text += std::string(72 - width - suffix.size(), ' ') + suffix;
      record(text);
      start = end;
    }
    return records;
  }
  int count() const { return count_; }

 private:
  // Whether the character at `at` lies inside a Hollerith string (nH...) of `text`.
  static bool insideHollerith(const std::string& text, size_t at) {
    for (size_t k = 0; k < at;) {
      if (std::isdigit(static_cast<unsigned char>(text[k])) && (k == 0 || text[k - 1] == ',' || text[k - 1] == ';')) {
        size_t h = k;
        while (h < text.size() && std::isdigit(static_cast<unsigned char>(text[h]))) ++h;
        if (h < text.size() && text[h] == 'H') {
          const size_t length = std::stoul(text.substr(k, h - k));
          if (at <= h + length) return true;
          k = h + length + 1;
          continue;
        }
        k = h;
        continue;
      }
      ++k;
    }
    return false;
  }
  std::ostream& out_;
  char letter_;
  int count_ = 0;
};

// "YYYYMMDD.HHNNSS" of an ISO 8601 timestamp "YYYY-MM-DDTHH:MM:SS".
std::string igesDate(const std::string& iso) {
  std::string digits;
  for (char c : iso)
    if (std::isdigit(static_cast<unsigned char>(c))) digits += c;
  digits.resize(14, '0');
  return digits.substr(0, 8) + "." + digits.substr(8, 6);
}

struct IgesUnit {
  CadUnit unit;
  int flag;
  const char* name;
};
constexpr IgesUnit kIgesUnits[] = {{CadUnit::Millimetre, 2, "MM"}, {CadUnit::Metre, 6, "M"}, {CadUnit::Inch, 1, "INCH"}};

std::string globalSection(const CadSurfaceSet& set, const CadFileInfo& info) {
  const IgesUnit& unit = *std::find_if(std::begin(kIgesUnits), std::end(kIgesUnits),
                                       [&](const IgesUnit& u) { return u.unit == info.unit; });
  const double maxCoordinate = std::max({std::abs(set.boxMin.x), std::abs(set.boxMin.y), std::abs(set.boxMin.z),
                                         std::abs(set.boxMax.x), std::abs(set.boxMax.y), std::abs(set.boxMax.z)});
  const double resolution = set.boxDiagonal > 0.0 ? 1e-7 * set.boxDiagonal : 1e-7;
  const std::string date = igesString(igesDate(info.timestamp));
  const std::vector<std::string> fields = {
      "1H,", "1H;",                     // parameter and record delimiters
      igesString(info.productName),    // product id of the sender
      igesString(info.fileName),       // file name
      igesString("polarview"),         // native system id
      igesString("polarview IGES 5.3 writer"),  // preprocessor version
      "32", "38", "6", "308", "15",     // integer bits; single and double precision: max power, digits
      igesString(info.productName),    // product id of the receiver
      "1.", std::to_string(unit.flag), igesString(unit.name),  // model space scale, units
      "1", "1.",                        // line weight gradations, max line weight (no lines drawn)
      date,                             // when the file was made
      igesReal(resolution), igesReal(maxCoordinate),
      igesString("polarview"), igesString("polarview"),  // author, organisation
      "11", "0",                        // IGES 5.3, no drafting standard
      date,                             // when the model was made
      igesString("")};                  // application protocol: none
  std::string text;
  for (size_t k = 0; k < fields.size(); ++k) text += fields[k] + (k + 1 < fields.size() ? "," : ";");
  return text;
}

// Entity 128's parameters for one surface (IGES 5.3, 4.24).
std::string surfaceParameters(const CadSurface& surface) {
  const BezierPatch& b = surface.bezier;
  std::string text = std::to_string(kSurfaceEntity) + "," + std::to_string(b.degU) + "," + std::to_string(b.degV) + "," +
                     std::to_string(b.degU) + "," + std::to_string(b.degV) + ",0,0,1,0,0,";
  for (double knot : clampedBezierKnots(b.degU)) text += igesReal(knot) + ",";
  for (double knot : clampedBezierKnots(b.degV)) text += igesReal(knot) + ",";
  for (size_t k = 0; k < b.cp.size(); ++k) text += "1.,";
  // Control points with the first (u) index fastest: cp(i, j) at k = i + (degU + 1) j.
  for (int j = 0; j <= b.degV; ++j)
    for (int i = 0; i <= b.degU; ++i) {
      const Point& p = b.cp[size_t((b.degV + 1) * i + j)];
      text += igesReal(p.x) + "," + igesReal(p.y) + "," + igesReal(p.z) + ",";
    }
  return text + "0.,1.,0.,1.;";
}

const char* surfaceLabel(PatchKind kind) {
  static const char* const labels[] = {"REGULAR", "BOUNDARY", "RING", "CAP", "ENDCAP"};
  return labels[size_t(kind)];
}

}  // namespace

std::string igesString(const std::string& text) {
  std::string clean;
  for (char c : text) clean += (c >= 32 && c < 127) ? c : '_';
  return std::to_string(clean.size()) + "H" + clean;
}

std::string igesReal(double value) { return cadReal(value, 'D'); }

void writeIges(std::ostream& out, const CadSurfaceSet& set, const CadFileInfo& info) {
  IgesSection start(out, 'S');
  start.record(("polarview: " + info.description).substr(0, 72));
  IgesSection global(out, 'G');
  global.stream(globalSection(set, info), 72, "");

  // Parameter data first into memory: the directory entries need each entity's first record and
  // record count.
  std::vector<std::string> parameters;
  parameters.reserve(set.surfaces.size());
  for (const CadSurface& surface : set.surfaces) parameters.push_back(surfaceParameters(surface));
  std::vector<int> firstRecord(parameters.size()), recordCount(parameters.size());
  // The records a parameter string breaks into (as IgesSection::stream breaks it), counted on a
  // null stream so the directory can point at them before they are written.
  std::ostream null(nullptr);
  int next = 1;
  for (size_t k = 0; k < parameters.size(); ++k) {
    IgesSection counter(null, 'P');
    firstRecord[k] = next;
    recordCount[k] = counter.stream(parameters[k], 64, "");
    next += recordCount[k];
  }

  IgesSection directory(out, 'D');
  for (size_t k = 0; k < set.surfaces.size(); ++k) {
    const CadSurface& surface = set.surfaces[k];
    char line[96];
    std::snprintf(line, sizeof line, "%8d%8d%8d%8d%8d%8d%8d%8d%8s", kSurfaceEntity, firstRecord[k], 0, 0, 0, 0, 0, 0, "00000000");
    directory.record(line);
    std::snprintf(line, sizeof line, "%8d%8d%8d%8d%8d%8s%8s%8s%8zu", kSurfaceEntity, 0, 0, recordCount[k], 0, "", "",
                  surfaceLabel(surface.kind), surface.patch % 100000000);
    directory.record(line);
  }
  IgesSection parameterData(out, 'P');
  for (size_t k = 0; k < parameters.size(); ++k) {
    char pointer[24];
    std::snprintf(pointer, sizeof pointer, "%7zu", 2 * k + 1);
    parameterData.stream(parameters[k], 64, std::string(pointer));
  }
  IgesSection terminate(out, 'T');
  char counts[80];
  std::snprintf(counts, sizeof counts, "S%7dG%7dD%7dP%7d", start.count(), global.count(), directory.count(), parameterData.count());
  terminate.record(counts);
}

}  // namespace polarview
