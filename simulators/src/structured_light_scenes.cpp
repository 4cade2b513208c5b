#include "keyturn/sim/structured_light_scenes.h"

namespace keyturn::sim {

std::shared_ptr<const StructuredLightRenderer> StructuredLightScenes::take(const std::string& key,
                                                                           const Build& build) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    // use_count() is exact here: only take() adds holders, and only under this lock.
    for (auto it = scenes_.begin(); it != scenes_.end(); ++it)
      if (it->first == key && it->second.use_count() == 1) {
        scenes_.splice(scenes_.begin(), scenes_, it);
        return scenes_.front().second;
      }
  }
  std::shared_ptr<const StructuredLightRenderer> made = build();
  std::lock_guard<std::mutex> lock(mutex_);
  ++built_;
  scenes_.emplace_front(key, made);
  // Forget the least recently taken idle ones beyond `keep_`, counting the one just built (idle once
  // its holder lets go). Those others hold stay, and count once released, at the next build.
  std::size_t kept = 0;
  for (auto it = scenes_.begin(); it != scenes_.end();) {
    const bool is_new = it == scenes_.begin();
    const bool idle = it->second.use_count() == 1;
    if (is_new || idle) ++kept;
    if (!is_new && idle && kept > keep_) {
      it = scenes_.erase(it);
    } else {
      ++it;
    }
  }
  return made;
}

std::size_t StructuredLightScenes::built() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return built_;
}

}  // namespace keyturn::sim
