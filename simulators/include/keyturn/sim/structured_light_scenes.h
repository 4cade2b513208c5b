#pragma once
// Structured-light scenes kept once built: a simulated camera opened again (a reconnect, a replug,
// the next program run in the same process) gets its renderer back with the mesh's BVH, the table's
// pixels and the per-pixel noise model already cast, instead of building them during its first frame.
// A renderer is handed to one holder at a time (its cast state is not shared between threads): a
// second camera of the same scene open at once gets a renderer of its own.
#include <cstddef>
#include <functional>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

#include "keyturn/sim/structured_light_view.h"

namespace keyturn::sim {

class StructuredLightScenes {
 public:
  using Build = std::function<std::unique_ptr<StructuredLightRenderer>()>;

  // Keeps up to `keep` renderers no one holds (about 10 MB each at 640 × 480), the most recently
  // taken; one held stays while it is held.
  explicit StructuredLightScenes(std::size_t keep = 4) : keep_(keep) {}

  // A renderer of the scene `key` names that no one else holds: a kept one, or one `build` makes
  // (outside the lock: a slow build does not hold up other opens). `build`'s exceptions pass through.
  std::shared_ptr<const StructuredLightRenderer> take(const std::string& key, const Build& build);

  // Renderers built by take() so far.
  std::size_t built() const;

 private:
  using Entry = std::pair<std::string, std::shared_ptr<const StructuredLightRenderer>>;
  std::size_t keep_;
  mutable std::mutex mutex_;
  std::list<Entry> scenes_;  // most recently taken first
  std::size_t built_ = 0;
};

}  // namespace keyturn::sim
