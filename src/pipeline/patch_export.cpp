// `polarview export`'s two halves: the patches (feature-adaptive or uniform) and the atomic .bv
// file (core/spline/bezierview_export.h says what is written and how exact it is). The command
// itself (options, budget, summary) is runExport in cli_commands.cpp.
#include "pipeline/patch_export.h"

#include <ostream>
#include <streambuf>
#include <string_view>

#include "core/mesh/atomic_file.h"
#include "core/subdiv/adaptive_refiner.h"
#include "core/subdiv/refiner.h"

namespace polarview {

namespace {

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

PatchSet exportPatchSet(const PolyMesh& mesh, const RefineOptions& options, const std::string& source, bool uniform,
                        size_t maxFaces) {
  if (uniform) return extractPatches(Refinement(mesh, options, source, maxFaces));
  return extractPatches(AdaptiveRefinement(mesh, options, source, maxFaces));
}

void writeStreamAtomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  // Through an atomic file: any error (here or in the writer) leaves no output behind.
  AtomicFileWriter file(path);
  AtomicFileBuffer buffer(file);
  std::ostream stream(&buffer);
  stream.exceptions(std::ios::badbit | std::ios::failbit);
  write(stream);
  stream.flush();
  file.commit();
}

BezierViewStats writeBezierViewFile(const std::string& path, const PatchSet& set, const std::string& source) {
  BezierViewStats stats;
  writeStreamAtomically(path, [&](std::ostream& out) { stats = writeBezierView(out, set, BezierViewOptions{}, source); });
  return stats;
}

UniformLevelEstimate estimateUniformLevel(const PolyMesh& mesh, const RefineOptions& options, bool radial, size_t maxFaces) {
  auto facesAt = [&](int level) {
    RefineOptions at = options;
    at.levels = level;
    return estimateFaceCount(mesh, at, radial);
  };
  UniformLevelEstimate estimate{facesAt(options.levels), options.levels, true};
  estimate.fits = estimate.faces <= maxFaces;
  while (estimate.deepestFitting > 0 && facesAt(estimate.deepestFitting) > maxFaces) --estimate.deepestFitting;
  return estimate;
}

}  // namespace polarview
