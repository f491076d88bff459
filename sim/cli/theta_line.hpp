// One line of `curio-sim rollout` input: 49 numbers in [−1, 1] separated by whitespace
// and/or single commas; blank lines and lines starting with '#' carry no θ.
#pragma once
#include <string>
#include <string_view>

#include "firmware/explore/config.hpp"

namespace curio::sim {

enum class ThetaLineStatus { kTheta, kSkip, kError };

// On kError, *error says what is wrong (without the line number).
ThetaLineStatus parse_theta_line(std::string_view line, float theta[kThetaDim], std::string* error);

}  // namespace curio::sim
