// The commands code names (the panels' buttons, the app, `view --inspect-poles`), as constants in
// place of string literals: tests/session/command_table_test.cpp checks that each is a row of the
// command table (session/command_table.h), and CommandTable::at fails loudly on any other id.
// A command that only keys, help and `view --do` reach needs no constant here.
#pragma once

#include <string_view>

// X(constant, id): one line a command the code names.
#define POLARVIEW_NAMED_COMMANDS(X)                          \
  X(kFileOpen, "file.open")                                  \
  X(kFileReload, "file.reload")                              \
  X(kFileDefault, "file.default")                            \
  X(kFilePreviousModel, "file.previous-model")               \
  X(kEditUndo, "edit.undo")                                  \
  X(kEditRedo, "edit.redo")                                  \
  X(kEditReset, "edit.reset")                                \
  X(kEditSave, "edit.save")                                  \
  X(kExportSurface, "export.surface")                        \
  X(kExportRefinedObj, "export.refined-obj")                 \
  X(kModelEvToPolar, "model.ev-to-polar")                    \
  X(kModelEvToPolarPentagons, "model.ev-to-polar-pentagons") \
  X(kModelNgonToFan, "model.ngon-to-fan")                    \
  X(kModelEigenvector, "model.eigenvector")                  \
  X(kCameraFrame, "camera.frame")                            \
  X(kCameraFront, "camera.front")                            \
  X(kCameraTop, "camera.top")                                \
  X(kCameraSide, "camera.side")                              \
  X(kCameraIso, "camera.iso")                                \
  X(kCameraCopy, "camera.copy")                              \
  X(kCameraPaste, "camera.paste")                            \
  X(kShade, "shade")                                         \
  X(kScreenshot, "screenshot")                               \
  X(kPolesInspect, "poles.inspect")                          \
  X(kSurfaceMeasure, "surface.measure")

namespace polarview::command_ids {

#define POLARVIEW_COMMAND_CONSTANT(name, id) inline constexpr std::string_view name = id;
POLARVIEW_NAMED_COMMANDS(POLARVIEW_COMMAND_CONSTANT)
#undef POLARVIEW_COMMAND_CONSTANT

// Every constant above (the test walks them).
#define POLARVIEW_COMMAND_ENTRY(name, id) name,
inline constexpr std::string_view kAll[] = {POLARVIEW_NAMED_COMMANDS(POLARVIEW_COMMAND_ENTRY)};
#undef POLARVIEW_COMMAND_ENTRY

}  // namespace polarview::command_ids
