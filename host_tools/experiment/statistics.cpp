#include "host_tools/experiment/statistics.hpp"

#include <cmath>

namespace curio::lab {

double student_t_975(int dof) {
  // Exact table up to 30 degrees of freedom, normal quantile beyond.
  static constexpr double kTable[] = {0,      12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365,
                                      2.306,  2.262,  2.228, 2.201, 2.179, 2.160, 2.145, 2.131,
                                      2.120,  2.110,  2.101, 2.093, 2.086, 2.080, 2.074, 2.069,
                                      2.064,  2.060,  2.056, 2.052, 2.048, 2.045, 2.042};
  if (dof <= 0) return 0.0;
  if (dof <= 30) return kTable[dof];
  return 1.959964;
}

Summary summarize(std::span<const double> values) {
  Summary s;
  s.n = static_cast<int>(values.size());
  if (s.n == 0) return s;
  double sum = 0.0;
  for (double v : values) sum += v;
  s.mean = sum / s.n;
  double ss = 0.0;
  for (double v : values) ss += (v - s.mean) * (v - s.mean);
  s.std = s.n > 1 ? std::sqrt(ss / (s.n - 1)) : 0.0;
  const double half = s.n > 1 ? student_t_975(s.n - 1) * s.std / std::sqrt(double(s.n)) : 0.0;
  s.ci95_low = s.mean - half;
  s.ci95_high = s.mean + half;
  return s;
}

}  // namespace curio::lab
