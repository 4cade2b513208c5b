// Device specs: the CLI's text read into typed values and written back (rig/device_spec.h).
#include <gtest/gtest.h>

#include <string>

#include "keyturn/rig/device_spec.h"
#include "support/error_of.h"

namespace keyturn {
namespace {

using test::errorOf;

TEST(CameraSpec, ReadsEveryKindOfCamera) {
  EXPECT_EQ(rig::CameraSpec::parse("sim").kind, rig::CameraSpec::Kind::Simulated);
  EXPECT_EQ(rig::CameraSpec::parse("sim").sim_config, "");
  EXPECT_EQ(rig::CameraSpec::parse("sim:rig/camera.json").sim_config, "rig/camera.json");
  const auto usb = rig::CameraSpec::parse("usb:4000123");
  EXPECT_EQ(usb.kind, rig::CameraSpec::Kind::Usb);
  EXPECT_EQ(usb.usb_serial, 4000123u);
  EXPECT_EQ(rig::CameraSpec::parse("usb").usb_serial, 0u);
  const auto eth = rig::CameraSpec::parse("eth:192.168.1.42,lib=/opt/mesa/libmesasr.so");
  EXPECT_EQ(eth.kind, rig::CameraSpec::Kind::Ethernet);
  EXPECT_EQ(eth.address, "192.168.1.42");
  EXPECT_EQ(eth.mesasr_library, "/opt/mesa/libmesasr.so");
  EXPECT_EQ(rig::CameraSpec::parse("usb,lib=/l.so").mesasr_library, "/l.so");
}

TEST(CameraSpec, ReadsAPlaybacksDatasetRateAndLooping) {
  const auto p = rig::CameraSpec::parse("playback:out/demo");
  EXPECT_EQ(p.kind, rig::CameraSpec::Kind::Playback);
  EXPECT_EQ(p.playback.dataset, "out/demo");
  EXPECT_EQ(p.playback.rate_fps, 0);
  EXPECT_TRUE(p.playback.loop);
  EXPECT_EQ(rig::CameraSpec::parse("playback:out/demo@12.5").playback.rate_fps, 12.5);
  EXPECT_EQ(rig::CameraSpec::parse("playback:out/demo@12.5").playback.dataset, "out/demo");
  EXPECT_EQ(rig::CameraSpec::parse("playback:runs/a@b").playback.dataset, "runs/a@b");  // not a rate: the folder's
  const auto once = rig::CameraSpec::parse("playback:out/demo@5@once");
  EXPECT_FALSE(once.playback.loop);
  EXPECT_EQ(once.playback.rate_fps, 5);
  EXPECT_EQ(once.playback.dataset, "out/demo");
}

TEST(CameraSpec, TheDisplayFormParsesBackToTheSameSpec) {
  for (const std::string text : {"sim", "sim:/tmp/a b/camera.json", "usb", "usb:4000123", "usb,lib=/opt/libmesasr.so",
                                 "usb:7,lib=/opt/libmesasr.so", "eth:10.0.0.2", "eth:10.0.0.2,lib=lib@2.so",
                                 "playback:out/demo", "playback:out/demo@12.5", "playback:runs/a@b",
                                 "playback:out/demo@once", "playback:x@0.25@once"}) {
    const rig::CameraSpec spec = rig::CameraSpec::parse(text);
    EXPECT_EQ(spec.toString(), text);
    EXPECT_EQ(rig::CameraSpec::parse(spec.toString()), spec) << text;
  }
  // Built field by field, as the studio does.
  rig::CameraSpec s;
  s.kind = rig::CameraSpec::Kind::Playback;
  s.playback = {"my@data", 1.0 / 3, false};
  EXPECT_EQ(rig::CameraSpec::parse(s.toString()), s) << s.toString();
  s.playback.rate_fps = 0;
  EXPECT_EQ(rig::CameraSpec::parse(s.toString()), s) << s.toString();
  // Any field that differs makes another spec.
  EXPECT_NE(rig::CameraSpec::parse("usb:1"), rig::CameraSpec::parse("usb:2"));
  EXPECT_NE(rig::CameraSpec::parse("usb"), rig::CameraSpec::parse("usb,lib=x.so"));
  EXPECT_NE(rig::CameraSpec::parse("sim"), rig::CameraSpec::parse("sim:c.json"));
}

TEST(CameraSpec, ReadsOpenNi2DevicesAndOniRecordings) {
  const auto any = rig::CameraSpec::parse("openni2");
  EXPECT_EQ(any.kind, rig::CameraSpec::Kind::OpenNi2);
  EXPECT_EQ(any.openni2_uri, "");
  EXPECT_EQ(any.describe(), "OpenNI2 camera");
  // OpenNI2's URIs hold '@', '/' and ':' and are taken verbatim (a PS1080's, the simulated driver's).
  const auto xtion = rig::CameraSpec::parse("openni2:1d27/0601@2/7");
  EXPECT_EQ(xtion.openni2_uri, "1d27/0601@2/7");
  EXPECT_EQ(rig::CameraSpec::parse("openni2:keyturn-sim:///tmp/a b/sim.json").openni2_uri,
            "keyturn-sim:///tmp/a b/sim.json");
  // A playback path ending in .oni is OpenNI2's recording; any other stays a keyturn dataset.
  const auto oni = rig::CameraSpec::parse("playback:rec/take 1.oni@15@once");
  EXPECT_EQ(oni.kind, rig::CameraSpec::Kind::OniFile);
  EXPECT_EQ(oni.playback.dataset, "rec/take 1.oni");
  EXPECT_EQ(oni.playback.rate_fps, 15);
  EXPECT_FALSE(oni.playback.loop);
  EXPECT_EQ(oni.describe(), "OpenNI2 recording rec/take 1.oni");
  EXPECT_EQ(rig::CameraSpec::parse("playback:rec/oni").kind, rig::CameraSpec::Kind::Playback);
  EXPECT_EQ(rig::CameraSpec::parse("playback:rec.oni.d").kind, rig::CameraSpec::Kind::Playback);
  for (const std::string text : {"openni2", "openni2:1d27/0601@2/7", "openni2:keyturn-sim://default",
                                 "playback:a.oni", "playback:a.oni@15", "playback:x/a.oni@once", "playback:b@c.oni@2.5@once"}) {
    const rig::CameraSpec spec = rig::CameraSpec::parse(text);
    EXPECT_EQ(spec.toString(), text);
    EXPECT_EQ(rig::CameraSpec::parse(spec.toString()), spec) << text;
  }
  EXPECT_NE(rig::CameraSpec::parse("openni2"), rig::CameraSpec::parse("openni2:1d27/0601@2/7"));
  EXPECT_NE(rig::CameraSpec::parse("playback:a.oni"), rig::CameraSpec::parse("playback:a.oni@once"));
}

TEST(CameraSpec, ABadCameraIsOneLineNamingEveryChoice) {
  const std::string choices =
      "expected sim, sim:CONFIG, usb, usb:SERIAL, eth:IP, openni2, openni2:URI, playback:DATASET[@FPS][@once] or "
      "playback:FILE.oni[@FPS][@once] (usb and eth take ,lib=LIBMESASR)";
  EXPECT_EQ(errorOf([] { rig::CameraSpec::parse("gige"); }), "camera 'gige': " + choices);
  EXPECT_EQ(errorOf([] { rig::CameraSpec::parse("usb:abc"); }),
            "camera 'usb:abc': expected usb:SERIAL with a number; " + choices);
  EXPECT_EQ(errorOf([] { rig::CameraSpec::parse("eth:10.0.0"); }),
            "camera 'eth:10.0.0': expected eth:IPv4-ADDRESS; " + choices);
  EXPECT_EQ(errorOf([] { rig::CameraSpec::parse("usb:1,library=x"); }),
            "camera 'usb:1,library=x': unknown option 'library=x'; " + choices);
  EXPECT_EQ(errorOf([] { rig::CameraSpec::parse("sim:"); }),
            "camera 'sim:': sim: needs the simulator's configuration file; " + choices);
  EXPECT_EQ(errorOf([] { rig::CameraSpec::parse("openni2:"); }),
            "camera 'openni2:': openni2: needs the device's URI (keyturn devices lists them); " + choices);
  EXPECT_EQ(errorOf([] { rig::CameraSpec::parse("openni"); }), "camera 'openni': " + choices);
  EXPECT_EQ(errorOf([] { rig::CameraSpec::parse("playback:out/demo@0"); }),
            "camera 'playback:out/demo@0': the playback rate after @ must be a positive number of frames/s");
  EXPECT_EQ(errorOf([] { rig::CameraSpec::parse("playback:"); }),
            "camera 'playback:': playback needs a dataset folder (playback:DATASET[@FPS][@once])");
  for (const char* bad : {"gige", "usb:abc", "eth:x", "playback:", "sim:"})
    EXPECT_EQ(errorOf([bad] { rig::CameraSpec::parse(bad); }).find('\n'), std::string::npos) << bad;
}

TEST(PoseSpec, ReadsEveryKindOfPoseSource) {
  EXPECT_EQ(rig::PoseSpec::parse("sim").kind, rig::PoseSpec::Kind::Simulated);
  EXPECT_EQ(rig::PoseSpec::parse("playback").kind, rig::PoseSpec::Kind::Playback);
  EXPECT_EQ(rig::PoseSpec::parse("playback").playback.dataset, "");
  EXPECT_EQ(rig::PoseSpec::parse("playback:rec@2").playback.rate_fps, 2);
  const auto tcp = rig::PoseSpec::parse("modbus-tcp:10.0.0.7:1502@3,profile=generic-encoder");
  EXPECT_EQ(tcp.kind, rig::PoseSpec::Kind::ModbusTcp);
  EXPECT_EQ(tcp.modbus.host, "10.0.0.7");
  EXPECT_EQ(tcp.modbus.port, 1502);
  EXPECT_EQ(tcp.modbus.unit_id, 3);
  EXPECT_EQ(tcp.profile, "generic-encoder");
  const auto rtu = rig::PoseSpec::parse("modbus-rtu:/dev/ttyUSB0:9600:8E1");
  EXPECT_EQ(rtu.kind, rig::PoseSpec::Kind::ModbusRtu);
  EXPECT_EQ(rtu.modbus.device, "/dev/ttyUSB0");
  EXPECT_EQ(rtu.modbus.baud, 9600);
  EXPECT_EQ(rtu.modbus.parity, 'E');
  const auto can = rig::PoseSpec::parse("can:vcan0,profile=axes.json");
  EXPECT_EQ(can.kind, rig::PoseSpec::Kind::Can);
  EXPECT_EQ(can.can_interface, "vcan0");
  EXPECT_EQ(can.profile, "axes.json");
}

TEST(PoseSpec, TheDisplayFormParsesBackToTheSameSpec) {
  for (const std::string text : {"sim", "playback", "playback:rec", "playback:rec@2@once", "modbus-tcp:127.0.0.1:1502",
                                 "modbus-tcp:h:502@7,profile=/etc/table.json", "modbus-rtu:/dev/ttyUSB0:115200:8N1",
                                 "modbus-rtu:/dev/ttyS1:9600:7E2@12,profile=generic-encoder", "can:can0",
                                 "can:vcan0,profile=axes.json"}) {
    const rig::PoseSpec spec = rig::PoseSpec::parse(text);
    EXPECT_EQ(spec.toString(), text);
    EXPECT_EQ(rig::PoseSpec::parse(spec.toString()), spec) << text;
  }
  // A short form is written out whole, and reads back to the same endpoint.
  const auto rtu = rig::PoseSpec::parse("modbus-rtu:/dev/ttyUSB0");
  EXPECT_EQ(rtu.toString(), "modbus-rtu:/dev/ttyUSB0:115200:8N1");
  EXPECT_EQ(rig::PoseSpec::parse(rtu.toString()), rtu);
  EXPECT_NE(rig::PoseSpec::parse("modbus-tcp:h:502@2"), rig::PoseSpec::parse("modbus-tcp:h:502@3"));
  EXPECT_NE(rig::PoseSpec::parse("modbus-rtu:/dev/a:9600"), rig::PoseSpec::parse("modbus-rtu:/dev/a:19200"));
}

TEST(PoseSpec, ABadPoseSourceIsOneLineNamingEveryChoice) {
  const std::string choices =
      "expected sim, playback, playback:DATASET, modbus-tcp:HOST:PORT[@UNIT], modbus-rtu:DEVICE[:BAUD[:8N1]][@UNIT] "
      "or can:IFACE (modbus and can take ,profile=FILE)";
  EXPECT_EQ(errorOf([] { rig::PoseSpec::parse("serial"); }), "pose 'serial': " + choices);
  EXPECT_EQ(errorOf([] { rig::PoseSpec::parse("modbus-tcp:h:70000"); }),
            "pose source 'modbus-tcp:h:70000': bad host or port; " + choices);
  EXPECT_EQ(errorOf([] { rig::PoseSpec::parse("can:"); }), "pose 'can:': can: needs the CAN interface; " + choices);
  EXPECT_EQ(errorOf([] { rig::PoseSpec::parse("can:can0,axes=a.json"); }),
            "pose 'can:can0,axes=a.json': unknown option 'axes=a.json'; " + choices);
}

}  // namespace
}  // namespace keyturn
