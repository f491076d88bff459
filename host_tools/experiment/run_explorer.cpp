#include "host_tools/experiment/run_explorer.hpp"

namespace curio::lab {

bool make_run_explorer(const RunSpec& spec, RunExplorer* x, std::string* error) {
  x->rep = representation_of(spec);
  if (spec.algorithm.outcome == OutcomeSource::kLatents && x->rep == nullptr) {
    *error = "no weights for representation '" + spec.algorithm.representation +
             "' in this build (firmware/nn/models/" + spec.algorithm.representation +
             "_weights.hpp missing)";
    return false;
  }
  if (const Status s = make_explorer_config(spec, &x->config); s != Status::kOk) {
    *error = std::string("invalid explorer configuration: ") + to_string(s);
    return false;
  }
  x->explorer = std::make_unique<Explorer>();
  if (const Status s = x->explorer->init(x->config); s != Status::kOk) {
    *error = std::string("explorer init failed: ") + to_string(s);
    return false;
  }
  if (x->rep) x->encoder = std::make_unique<nn::Encoder>(*x->rep->model);
  return true;
}

}  // namespace curio::lab
