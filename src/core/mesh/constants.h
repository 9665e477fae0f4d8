// Numbers the core and the layers above share: the one definition of pi (every file that needs it
// includes this header rather than typing the digits again).
#pragma once

namespace polarview {

constexpr double kPi = 3.14159265358979323846264338327950288;
constexpr double kTwoPi = 6.283185307179586476925286766559;  // 2 kPi: the same double (doubling is exact)

}  // namespace polarview
