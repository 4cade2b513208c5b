#pragma once
// The simulated OpenNI2 device's own properties (device properties, read with
// openni::Device::getProperty; ids outside OpenNI's and PS1080's ranges): how its
// scene was prepared, for tests and for a person checking where time goes.
namespace keyturn::sim::openni2 {

// int: scenes (the mesh's BVH, the table's pixels, the per-pixel noise model) the driver has built
// since it was loaded; opening a device whose scene is kept builds none (sim_device.h).
inline constexpr int kScenesBuiltProperty = 0x4B540001;
// int: geometry casts of the device's scene so far, including those made for earlier opens of it.
// 1 after a fresh open: the open cast it, so the first frame only draws noise.
inline constexpr int kSceneCastsProperty = 0x4B540002;

}  // namespace keyturn::sim::openni2
