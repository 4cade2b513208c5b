#pragma once
// What device to open, as a value: the camera and the pose source every front end names (the CLI's
// --camera/--pose text, the studio's Devices panel) before rig/device_factory.h opens them. A new
// kind of camera is one more Kind here, its text in parse/toString, and its case in the factory.
//
// Text forms (parse reads them, toString writes them, describe says them to a person):
//   camera  sim[:CONFIG]                    libmesasr-sim; CONFIG: its configuration (JSON), else its defaults
//           usb[:SERIAL][,lib=LIBMESASR]    an SR4000 on USB (0 or none: the first found)
//           eth:IP[,lib=LIBMESASR]          an SR4000 on Ethernet; lib: MESA's library (default
//                                           $KEYTURN_MESASR_LIB, then the usual sonames)
//           playback:DATASET[@FPS][@once]   a dataset replayed (dataset_playback.h): at FPS (default the
//                                           recorded rate), looping unless "once"
//           openni2[:URI]                   a depth camera through OpenNI2 (Kinect, Xtion, Astra; the
//                                           first found, or the one with OpenNI2's URI, verbatim)
//           playback:FILE.oni[@FPS][@once]  an OpenNI2 recording (a path ending in .oni) played as a camera
//   pose    sim                             the simulated turntable sharing the simulated camera's world
//           playback[:DATASET[@FPS][@once]] the poses of the camera's recording (or of DATASET)
//           modbus-tcp:HOST:PORT[@UNIT][,profile=P]            a Modbus turntable or encoder; P: its
//           modbus-rtu:DEVICE[:BAUD[:8N1]][@UNIT][,profile=P]  register map (default keyturn-sim)
//           can:IFACE[,profile=AXES]        CANopen axes over SocketCAN, described by the AXES file
#include <string>

#include "keyturn/drivers/modbus_turntable.h"

namespace keyturn::rig {

// A dataset played back: the camera's frames and, optionally, the pose source's poses.
struct PlaybackSpec {
  std::string dataset;
  double rate_fps = 0;  // 0: the recorded rate
  bool loop = true;
  bool operator==(const PlaybackSpec& o) const { return dataset == o.dataset && rate_fps == o.rate_fps && loop == o.loop; }
};

struct CameraSpec {
  // The studio's camera list shows the first five in this order.
  enum class Kind { Simulated, Usb, Ethernet, Playback, OpenNi2, OniFile };
  Kind kind = Kind::Simulated;
  std::string sim_config;      // Simulated: libmesasr-sim's configuration file; empty: the simulator's defaults
  unsigned usb_serial = 0;     // Usb: 0 = the first camera found
  std::string address;         // Ethernet: IPv4
  std::string mesasr_library;  // Usb, Ethernet: MESA's libMesaSR; empty: $KEYTURN_MESASR_LIB or the usual sonames
  PlaybackSpec playback;       // Playback; OniFile: its dataset is the .oni file
  std::string openni2_uri;     // OpenNi2: empty = the first device found

  // The text forms above; anything else throws keyturn::Error in one line naming every choice.
  static CameraSpec parse(const std::string& text);
  std::string toString() const;  // parses back to this spec
  std::string describe() const;  // "simulated SR4000", "SR4000 4000123 on USB", "SR4000 at 10.0.0.2", "recording D",
                                 // "OpenNI2 camera", "OpenNI2 recording F.oni"
  bool operator==(const CameraSpec& o) const;
  bool operator!=(const CameraSpec& o) const { return !(*this == o); }
};

struct PoseSpec {
  enum class Kind { Simulated, Playback, ModbusTcp, ModbusRtu, Can };
  Kind kind = Kind::Simulated;
  drivers::ModbusEndpoint modbus;  // ModbusTcp, ModbusRtu
  std::string can_interface;       // Can
  std::string profile;             // Modbus: register map (file, generic-encoder, keyturn-sim; empty: keyturn-sim);
                                   // Can: the CANopen axes file (required)
  PlaybackSpec playback;           // Playback: empty dataset = the camera's recording

  static PoseSpec parse(const std::string& text);
  std::string toString() const;
  std::string describe() const;  // "simulated turntable", "Modbus TCP turntable at 127.0.0.1:1502", …
  bool operator==(const PoseSpec& o) const;
  bool operator!=(const PoseSpec& o) const { return !(*this == o); }
};

}  // namespace keyturn::rig
