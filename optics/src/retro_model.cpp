#include "airr/optics/retro_model.hpp"

#include "airr/optics/error.hpp"

namespace airr {

std::unique_ptr<retro_model> make_retro_model(const retro_model_params& p) {
  switch (p.type) {
    case retro_model_type::ideal:
      return std::make_unique<ideal_retro>(p.mu);
    case retro_model_type::sinc_shift:
    case retro_model_type::microfacet:
      break;
  }
  throw input_error(std::string("retroreflector.model.type: model '") + retro_model_type_names[int(p.type)] +
                    "' is not available in this build");
}

}  // namespace airr
