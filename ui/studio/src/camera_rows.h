#pragma once
// The Devices panel's camera Source list, row by row: the kind of rig::CameraSpec each row chooses.
// The list is built from this table and read through it, so a row and its kind cannot drift apart
// (the panel cast the row number to the Kind). An OpenNI2 recording (OniFile) is chosen as a
// recording: a path ending in .oni.
#include <QtGlobal>
#include <cstddef>

#include "keyturn/rig/device_spec.h"

namespace keyturn::studio {

struct CameraRow {
  rig::CameraSpec::Kind kind;
  const char* label;  // untranslated
};

inline constexpr CameraRow kCameraRows[] = {
    {rig::CameraSpec::Kind::Simulated, QT_TR_NOOP("Simulated SR4000")},
    {rig::CameraSpec::Kind::Usb, QT_TR_NOOP("USB")},
    {rig::CameraSpec::Kind::Ethernet, QT_TR_NOOP("Ethernet")},
    {rig::CameraSpec::Kind::Playback, QT_TR_NOOP("Recording (playback)")},
    {rig::CameraSpec::Kind::OpenNi2, QT_TR_NOOP("OpenNI2 (Kinect, Xtion, Astra)")},
};

// The row's kind (a row out of range: the first row's), and the row of a kind.
rig::CameraSpec::Kind cameraKindOfRow(int row);
int rowOfCameraKind(rig::CameraSpec::Kind kind);

}  // namespace keyturn::studio
