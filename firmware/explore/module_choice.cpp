#include "firmware/explore/module_choice.hpp"

namespace curio {

double module_probability(const float* interest, int n, float epsilon, int i) {
  double sum = 0.0;
  for (int k = 0; k < n; ++k) sum += static_cast<double>(interest[k]);
  const double uniform = 1.0 / static_cast<double>(n);
  if (sum <= 0.0) return uniform;
  const double eps = static_cast<double>(epsilon);
  return (1.0 - eps) * static_cast<double>(interest[i]) / sum + eps * uniform;
}

int choose_module(const float* interest, int n, float epsilon, Prng& prng) {
  const double u = prng.uniform01();
  double cumulative = 0.0;
  for (int i = 0; i < n - 1; ++i) {
    cumulative += module_probability(interest, n, epsilon, i);
    if (u < cumulative) return i;
  }
  return n - 1;
}

}  // namespace curio
