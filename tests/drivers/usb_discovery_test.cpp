// libusb discovery against devices emulated by umockdev: this binary runs under
// `umockdev-run -d sr4000.umockdev -d sr3000_old_ids.umockdev -d foreign_mouse.umockdev`.
#include <gtest/gtest.h>
#include <linux/capability.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include "keyturn/drivers/usb_discovery.h"
#include "support/ci_skip.h"

using namespace keyturn::drivers;

namespace {
bool underUmockdev() { return std::getenv("UMOCKDEV_DIR") != nullptr; }
}  // namespace

TEST(UsbDiscovery, KnowsTheSwissRangerIds) {
  EXPECT_STREQ(swissRangerModel(0x1ad2, 0x0075), "SR4000");
  EXPECT_STREQ(swissRangerModel(0x1ad2, 0x0074), "SR3000");
  EXPECT_STREQ(swissRangerModel(0x0852, 0x0074), "SR3000");
  EXPECT_EQ(swissRangerModel(0x1ad2, 0x0076), nullptr);
  EXPECT_EQ(swissRangerModel(0x046d, 0xc52b), nullptr);
}

TEST(UsbDiscovery, ListsTheCamerasAndIgnoresOtherDevices) {
  // ctest runs this binary under umockdev-run (Debian's, in scripts/install-deps.sh): on CI never a skip.
  if (!underUmockdev()) KEYTURN_SKIP_UNLESS_CI("needs umockdev-run (see tests/CMakeLists.txt)");
  const auto cams = listSwissRangerCameras();
  ASSERT_EQ(cams.size(), 2u);
  const auto& sr4k = cams[0].model == "SR4000" ? cams[0] : cams[1];
  const auto& sr3k = cams[0].model == "SR4000" ? cams[1] : cams[0];
  EXPECT_EQ(sr4k.bus, 1);
  EXPECT_EQ(sr4k.address, 5);
  EXPECT_EQ(sr4k.port_path, "1-2");
  EXPECT_EQ(sr4k.serial, "4000123");
  EXPECT_EQ(sr4k.node, "/dev/bus/usb/001/005");
  EXPECT_TRUE(sr4k.accessible);  // root
  EXPECT_EQ(sr3k.model, "SR3000");
  EXPECT_EQ(sr3k.vendor_id, 0x0852u);
  EXPECT_EQ(sr3k.port_path, "1-3.1");
  EXPECT_EQ(sr3k.serial, "");  // none in sysfs
}

TEST(UsbDiscovery, ADeviceThisUserMayNotOpenIsReportedWithTheUdevRule) {
  if (!underUmockdev()) KEYTURN_SKIP_UNLESS_CI("needs umockdev-run");
  // CI runs as root (as the Slurm test, which CI may not skip, needs): there this runs.
  if (::geteuid() != 0) KEYTURN_SKIP_UNLESS_CI("needs root to hand the device node to another user");
  // The SR4000's node belongs to another user, mode 0600. The child below gives
  // up root's permission override (libusb's udev monitor needs uid 0 under
  // umockdev, so it cannot simply become that other user).
  namespace fs = std::filesystem;
  const fs::path node = fs::path(std::getenv("UMOCKDEV_DIR")) / "dev/bus/usb/001/005";
  ASSERT_EQ(::chown(node.c_str(), 65534, 65534), 0);
  fs::permissions(node, fs::perms::owner_read | fs::perms::owner_write, fs::perm_options::replace);

  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    __user_cap_header_struct hdr{_LINUX_CAPABILITY_VERSION_3, 0};
    __user_cap_data_struct caps[2]{};
    if (::syscall(SYS_capget, &hdr, caps) != 0) ::_exit(2);
    const unsigned drop = (1u << CAP_DAC_OVERRIDE) | (1u << CAP_DAC_READ_SEARCH) | (1u << CAP_FOWNER);
    caps[0].effective &= ~drop;
    caps[0].permitted &= ~drop;
    if (::syscall(SYS_capset, &hdr, caps) != 0) ::_exit(2);
    std::string line;
    try {
      for (const auto& c : listSwissRangerCameras())
        line += c.model + (c.accessible ? " yes " : " no ") + c.access_error + "\n";
    } catch (const std::exception& e) {
      line = std::string("error: ") + e.what();
    }
    if (::write(fds[1], line.data(), line.size()) < 0) ::_exit(3);
    ::_exit(0);
  }
  ::close(fds[1]);
  std::string out;
  char buf[512];
  for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) > 0;) out.append(buf, static_cast<std::size_t>(n));
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  ASSERT_EQ(WEXITSTATUS(status), 0);
  EXPECT_NE(out.find("SR4000 no permission denied on /dev/bus/usb/001/005"), std::string::npos) << out;
  EXPECT_NE(out.find("SR3000 yes"), std::string::npos) << out;
  EXPECT_NE(swissRangerUdevRule().find("ATTRS{idVendor}==\"1ad2\""), std::string::npos);
}
