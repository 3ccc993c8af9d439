#include "app/version.hpp"

namespace fetic::app {

const char* fetic_version() {
  return FETIC_VERSION;
}

}  // namespace fetic::app
