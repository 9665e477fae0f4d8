// Numbers the core and the layers above share.
#pragma once

namespace polarview {

constexpr double kPi = 3.14159265358979323846264338327950288;

}  // namespace polarview
