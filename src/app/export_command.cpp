// `polarview export IN.obj --scheme S --level L -o OUT.bv [--uniform] [--memory-budget SIZE]`:
// refine, extract the patches, write them as BezierView patches (core/spline/bezierview_export.h),
// atomically, and print one summary line.
//
// Its options mean what they mean for `refine` (cli_commands.cpp: parseOptions, memory budget);
// they are parsed here because those helpers are private to cli_commands.cpp.
#include "app/export_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <ostream>
#include <streambuf>
#include <string_view>

#include "core/mesh/atomic_file.h"
#include "core/mesh/input_error.h"
#include "core/mesh/obj_io.h"
#include "core/spline/bezierview_export.h"
#include "core/subdiv/refiner.h"

namespace polarview::cli {

namespace {

// A usage error of `export`: printed with the usage text, exit code 2.
struct ExportUsageError {
  std::string what;
};

struct ExportOptions {
  std::string input, output;
  RefineOptions refine{Scheme::C2PS, -1, false};
  bool schemeGiven = false;
  bool uniform = false;
  size_t memoryBudget = 0;  // bytes; 0: 80% of the available memory
};

int parseLevel(const std::string& flag, const std::string& text) {
  try {
    size_t used = 0;
    const long v = std::stol(text, &used);
    if (used != text.size() || v < 0 || v > 64) throw std::out_of_range(text);
    return int(v);
  } catch (const std::exception&) {
    throw ExportUsageError{flag + " needs an integer in 0..64, got '" + text + "'"};
  }
}

// "2G", "500M", "64k", "123456" (bytes; binary units, optional trailing B), as refine reads it.
size_t parseByteSize(const std::string& flag, const std::string& text) {
  size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  std::string unit = text.substr(used);
  if (!unit.empty() && (unit.back() == 'B' || unit.back() == 'b')) unit.pop_back();
  double scale = 1.0;
  if (unit == "k" || unit == "K") scale = 1024.0;
  else if (unit == "m" || unit == "M") scale = 1024.0 * 1024.0;
  else if (unit == "g" || unit == "G") scale = 1024.0 * 1024.0 * 1024.0;
  else if (unit == "t" || unit == "T") scale = 1024.0 * 1024.0 * 1024.0 * 1024.0;
  else if (!unit.empty()) used = 0;
  if (used == 0 || !(value > 0.0) || !std::isfinite(value * scale) || value * scale > 1e18)
    throw ExportUsageError{flag + " expects a size such as 2G, 500M or a number of bytes, got '" + text + "'"};
  return size_t(value * scale);
}

// The scheme names of refine: parseScheme's plus "c2ps-u" / "rts-u" (the Section-6 first step).
std::optional<Scheme> parseExportScheme(const std::string& name, bool* uniformFirstStep) {
  *uniformFirstStep = false;
  for (Scheme s : {Scheme::C2PS, Scheme::RTS})
    if (name == std::string(schemeName(s)) + "-u") {
      *uniformFirstStep = true;
      return s;
    }
  return parseScheme(name);
}

ExportOptions parseExportOptions(const Args& args) {
  ExportOptions o;
  bool uniformFlag = false, uniformScheme = false;
  for (size_t k = 0; k < args.size(); ++k) {
    const std::string& a = args[k];
    auto next = [&]() -> const std::string& {
      if (k + 1 >= args.size()) throw ExportUsageError{a + " needs a value"};
      return args[++k];
    };
    if (a == "-o" || a == "--output") o.output = next();
    else if (a == "--scheme") {
      const std::optional<Scheme> s = parseExportScheme(next(), &uniformScheme);
      if (!s) throw ExportUsageError{"unknown scheme '" + args[k] + "' (cc, c2ps, c2ps-u, rts, rts-u, bps)"};
      o.refine.scheme = *s;
      o.schemeGiven = true;
    } else if (a == "--level" || a == "--levels") o.refine.levels = parseLevel(a, next());
    else if (a == "--uniform") o.uniform = true;
    else if (a == "--uniform-first-step") uniformFlag = true;
    else if (a == "--memory-budget") o.memoryBudget = parseByteSize(a, next());
    else if (a.size() > 1 && a[0] == '-') throw ExportUsageError{"unknown option " + a};
    else if (o.input.empty()) o.input = a;
    else throw ExportUsageError{"unexpected argument '" + a + "'"};
  }
  if (o.input.empty()) throw ExportUsageError{"missing input file"};
  if (o.output.empty()) throw ExportUsageError{"export needs -o OUT.bv"};
  if (!o.schemeGiven) throw ExportUsageError{"export needs --scheme S"};
  if (o.refine.levels < 0) throw ExportUsageError{"export needs --level L"};
  o.refine.uniformFirstStep = uniformFlag || uniformScheme;
  if (uniformFlag && o.refine.scheme != Scheme::C2PS && o.refine.scheme != Scheme::RTS)
    throw ExportUsageError{"export: --uniform-first-step applies to c2ps and rts only"};
  return o;
}

// Bytes an export takes per face of the finest level: refine's 300 (all levels' meshes and tables,
// measured 236-248 on a cube) plus one Patch (at most one patch per finest face, caps aside).
constexpr double kBytesPerFinestFace = 300.0 + double(sizeof(Patch));

// --memory-budget, else 80% of MemAvailable, else 4 GiB (as refine).
size_t memoryBudgetBytes(size_t requested) {
  if (requested > 0) return requested;
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  size_t kilobytes = 0;
  while (meminfo >> key >> kilobytes) {
    if (key == "MemAvailable:") return size_t(0.8 * double(kilobytes) * 1024.0);
    meminfo.ignore(1 << 10, '\n');
  }
  return size_t(4) << 30;
}

std::string gigabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g GB", bytes / 1e9);
  return text;
}

// Refuses, before anything is allocated, a level whose estimate exceeds the budget, naming the
// deepest level that fits (the message refine gives).
void checkMemoryBudget(const PolyMesh& mesh, const ExportOptions& o) {
  const size_t budget = memoryBudgetBytes(o.memoryBudget);
  const bool radial = refinesRadially(mesh, o.refine.scheme);
  auto bytesAt = [&](int level) {
    RefineOptions at = o.refine;
    at.levels = level;
    return double(estimateFaceCount(mesh, at, radial)) * kBytesPerFinestFace;
  };
  if (bytesAt(o.refine.levels) <= double(budget)) return;
  int fits = o.refine.levels;
  while (fits > 0 && bytesAt(fits) > double(budget)) --fits;
  throw InputError(o.input, 0,
                   "level " + std::to_string(o.refine.levels) + " would need about " + gigabytes(bytesAt(o.refine.levels)) +
                       ", over the memory budget of " + gigabytes(double(budget)) +
                       (o.memoryBudget > 0 ? " (--memory-budget)"
                                           : " (80% of the available memory; --memory-budget SIZE to change)") +
                       ": level " + std::to_string(fits) + " fits");
}

// A stream buffer that hands its bytes to an AtomicFileWriter in blocks (its errors propagate
// through the ostream, whose exceptions() must include badbit).
class AtomicFileBuffer : public std::streambuf {
 public:
  explicit AtomicFileBuffer(AtomicFileWriter& file) : file_(file) { setp(block_, block_ + sizeof block_); }

 protected:
  int_type overflow(int_type c) override {
    drain();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    drain();
    file_.write(std::string_view(s, size_t(n)));
    return n;
  }
  int sync() override {
    drain();
    return 0;
  }

 private:
  void drain() {
    if (pptr() > pbase()) file_.write(std::string_view(pbase(), size_t(pptr() - pbase())));
    setp(block_, block_ + sizeof block_);
  }
  AtomicFileWriter& file_;
  char block_[1 << 16];
};

}  // namespace

PatchSet exportPatchSet(const PolyMesh& mesh, const RefineOptions& options, const std::string& source, bool uniform) {
  if (uniform) return extractPatches(Refinement(mesh, options, source));
  // The adaptive path (a refiner that refines only where patches are missing) is not there yet:
  // the uniform refinement gives the same patches.
  return extractPatches(Refinement(mesh, options, source));
}

int runExport(const Args& args) {
  ExportOptions o;
  try {
    o = parseExportOptions(args);
  } catch (const ExportUsageError& e) {
    std::cerr << "polarview: " << e.what << "\n" << usageText();
    return 2;
  }
  std::vector<std::string> warnings;
  const PolyMesh mesh = loadObj(o.input, &warnings);
  for (const std::string& w : warnings) std::cerr << "polarview: warning: " << o.input << ": " << w << "\n";
  checkMemoryBudget(mesh, o);
  const PatchSet set = exportPatchSet(mesh, o.refine, o.input, o.uniform);

  // Write through an atomic file: any error (here or in the writer) leaves no output behind.
  AtomicFileWriter file(o.output);
  AtomicFileBuffer buffer(file);
  std::ostream stream(&buffer);
  stream.exceptions(std::ios::badbit | std::ios::failbit);
  const BezierViewStats stats = writeBezierView(stream, set, BezierViewOptions{}, o.input);
  stream.flush();
  file.commit();

  std::printf("%s: %zu Bezier patches in %zu groups (regular %zu, boundary %zu, polar-ring %zu, pole-cap %zu for %zu "
              "cap sectors, end-cap %zu)",
              o.output.c_str(), stats.total(), stats.groups, stats.written[size_t(PatchKind::Regular)],
              stats.written[size_t(PatchKind::Boundary)], stats.written[size_t(PatchKind::PolarRing)],
              stats.written[size_t(PatchKind::PoleCap)], stats.capSectors, stats.written[size_t(PatchKind::EndCap)]);
  if (stats.capSectors > 0)
    std::printf("; caps within %.2g of the bounding box (at most %d piece%s a cap sector)", stats.capRelativeDeviation(),
                stats.maxCapSplit, stats.maxCapSplit == 1 ? "" : "s");
  std::printf("\n");
  return 0;
}

}  // namespace polarview::cli
