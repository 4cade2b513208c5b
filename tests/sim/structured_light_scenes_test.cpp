// Scenes kept between opens of a simulated camera (keyturn/sim/structured_light_scenes.h): built once
// per scene while one is idle, never handed to two holders, forgotten beyond the number kept.
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>

#include "keyturn/sim/structured_light_scenes.h"

using namespace keyturn;

namespace {
sim::StructuredLightScenes::Build mug() {
  return [] { return std::make_unique<sim::StructuredLightRenderer>(sim::makeMugMesh()); };
}
}  // namespace

TEST(StructuredLightScenes, AReleasedSceneIsTakenAgainNotBuiltAgain) {
  sim::StructuredLightScenes scenes;
  const sim::StructuredLightRenderer* first = nullptr;
  {
    const auto r = scenes.take("mug", mug());
    first = r.get();
    sim::SceneView v;
    v.distance = 0.9;
    r->prepare(v);
  }
  const auto again = scenes.take("mug", mug());
  EXPECT_EQ(again.get(), first);
  EXPECT_EQ(scenes.built(), 1u);
  EXPECT_EQ(again->casts(), 1u);  // its cast came with it
}

TEST(StructuredLightScenes, TwoHoldersOfOneSceneGetARendererEach) {
  sim::StructuredLightScenes scenes;
  const auto a = scenes.take("mug", mug());
  const auto b = scenes.take("mug", mug());
  EXPECT_NE(a.get(), b.get());
  EXPECT_EQ(scenes.built(), 2u);
  const auto other = scenes.take("mug at 2x", mug());
  EXPECT_NE(other.get(), a.get());
  EXPECT_NE(other.get(), b.get());
  EXPECT_EQ(scenes.built(), 3u);
}

TEST(StructuredLightScenes, TheLeastRecentlyTakenIdleScenesAreForgottenBeyondTheNumberKept) {
  sim::StructuredLightScenes scenes(1);
  scenes.take("a", mug());
  scenes.take("b", mug());  // keeps b only
  scenes.take("b", mug());
  EXPECT_EQ(scenes.built(), 2u);
  scenes.take("a", mug());  // a was forgotten: built again
  EXPECT_EQ(scenes.built(), 3u);
  auto held = scenes.take("a", mug());
  EXPECT_EQ(scenes.built(), 3u);
  scenes.take("c", mug());  // beyond the one kept, but a is held: not forgotten
  EXPECT_EQ(scenes.built(), 4u);
  const sim::StructuredLightRenderer* a = held.get();
  held.reset();
  EXPECT_EQ(scenes.take("a", mug()).get(), a);
  EXPECT_EQ(scenes.built(), 4u);
}

TEST(StructuredLightScenes, AFailedBuildKeepsNothing) {
  sim::StructuredLightScenes scenes;
  EXPECT_THROW(scenes.take("bad", [] () -> std::unique_ptr<sim::StructuredLightRenderer> {
    throw std::runtime_error("bad.ply: no triangles");
  }), std::runtime_error);
  EXPECT_EQ(scenes.built(), 0u);
}
