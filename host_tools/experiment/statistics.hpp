// Summary statistics over seeds: mean, sample standard deviation and the 95 % confidence
// interval of the mean (Student's t, two-sided).
#pragma once
#include <span>

namespace curio::lab {

struct Summary {
  int n = 0;
  double mean = 0.0;
  double std = 0.0;      // sample standard deviation (n − 1)
  double ci95_low = 0.0;
  double ci95_high = 0.0;
};

Summary summarize(std::span<const double> values);

// Two-sided 97.5 % quantile of Student's t with `dof` degrees of freedom.
double student_t_975(int dof);

}  // namespace curio::lab
