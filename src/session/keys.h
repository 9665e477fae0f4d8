// Keys as the command table names them: GLFW's key codes and modifier bits (the window passes its
// events through unchanged; src/ui/input_events.cpp checks at compile time that the values agree),
// named here so the session needs no GLFW header.
#pragma once

namespace polarview::keys {

// Printable keys are their upper-case ASCII code ('A', '0', '[').
constexpr int kTab = 258, kPageUp = 266, kPageDown = 267, kF1 = 290, kF2 = 291, kF3 = 292, kF4 = 293;
constexpr int kKeypad0 = 320, kKeypadSubtract = 333, kKeypadAdd = 334;

constexpr int kShift = 0x1, kControl = 0x2, kAlt = 0x4;

}  // namespace polarview::keys
