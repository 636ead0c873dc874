// What the C face's files share (src/runtime/c_api*.cpp): the handles' C++ objects and the guard
// that turns every exception into an fg_error.
#pragma once

#include <algorithm>
#include <cstring>
#include <exception>
#include <limits>
#include <memory>
#include <new>

#include "fuzzygait/fuzzygait.h"
#include "fuzzygait/gait/controllers.hpp"
#include "fuzzygait/gait/crowd.hpp"
#include "fuzzygait/gait/walker.hpp"
#include "fuzzygait/rig/rig.hpp"
#include "fuzzygait/terrain/terrain.hpp"

struct fg_set {
  fuzzygait::gait::ControllerSet set;
};
struct fg_ground {
  fuzzygait::terrain::Terrain ground;
};
struct fg_walker {
  // Level ground of its own when none is given.
  std::unique_ptr<fuzzygait::terrain::Terrain> own_ground;
  fuzzygait::gait::Walker walker;
};
struct fg_crowd {
  std::unique_ptr<fuzzygait::terrain::Terrain> own_ground;
  fuzzygait::gait::Crowd crowd;
};

namespace fuzzygait::c_api {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

inline void clear(fg_error* error) {
  if (!error) return;
  error->failed = 0;
  error->message[0] = '\0';
}

inline void fail(fg_error* error, const char* message) {
  if (!error) return;
  error->failed = 1;
  const std::size_t n = std::min(std::strlen(message), sizeof error->message - 1);
  std::memcpy(error->message, message, n);
  error->message[n] = '\0';
}

// The segment lengths of a def.
inline void set_segments(fg_walker_def& def, const rig::Segments& s) {
  def.thigh = s.thigh;
  def.shank = s.shank;
  def.ankle_height = s.ankle_height;
  def.heel = s.heel;
  def.ball = s.ball;
  def.toe = s.toe;
}

// Runs `make`, turning any exception into `error` and a null result.
template <class Make>
auto guarded(fg_error* error, Make make) noexcept -> decltype(make()) {
  clear(error);
  try {
    return make();
  } catch (const std::bad_alloc&) {
    fail(error, "out of memory");
  } catch (const std::exception& e) {
    fail(error, e.what());
  } catch (...) {
    fail(error, "unknown error");
  }
  return nullptr;
}

}  // namespace fuzzygait::c_api
