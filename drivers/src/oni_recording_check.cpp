// The .oni container as OpenNI2's recorder writes it and libOniFile reads it (format learned from
// OpenNI2's public sources, Source/Drivers/OniFile/DataRecords.h and PlayerNode.cpp; this is
// keyturn's own reading of it). Little-endian throughout:
//   file header, 24 bytes: "NI10", version (u8 major, u8 minor, u16 maintenance, u32 build),
//     u64 largest timestamp, u32 largest node id;
//   records from byte 24 to the end record, each a header — "NIR\0", u32 type, u32 node id,
//     u32 fields size (header included), u32 payload size, undo position (u64; u32 in files
//     older than 1.0.1.0) — then its fields, then its payload.
// A string field is a u32 length (its NUL included) and the bytes. What follows the end record
// (the recorder leaves zeros there) is never read.
#include "keyturn/drivers/oni_recording_check.h"

#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "keyturn/core/error.h"

namespace keyturn::drivers {
namespace {

// libOniFile's buffers: one record (fields and payload) and one decoded frame (1600 × 1200 × 3).
constexpr std::uint64_t kFrameBufferBytes = 1600ull * 1200 * 3;
constexpr std::uint64_t kRecordBufferBytes = kFrameBufferBytes + 28 + 81 + 8 + 4;
constexpr std::uint32_t kMaxNameBytes = 80;         // node and property names, NUL included (XN_MAX_NAME_LENGTH)
constexpr std::uint32_t kMaxFieldsBytes = 1 << 20;  // far above any property a recorder writes
constexpr std::uint32_t kMaxNodeId = 255;           // libOniFile allocates a table of this many + 1
constexpr std::uint32_t kMaxModes = 1000;

enum RecordType : std::uint32_t {
  kNodeAdded1004 = 0x02,
  kIntProperty = 0x03,
  kRealProperty = 0x04,
  kStringProperty = 0x05,
  kGeneralProperty = 0x06,
  kNodeRemoved = 0x07,
  kNodeDataBegin = 0x08,
  kNodeStateReady = 0x09,
  kNewData = 0x0A,
  kEnd = 0x0B,
  kNodeAdded1005 = 0x0C,
  kNodeAdded = 0x0D,
  kSeekTable = 0x0E,
};

constexpr std::uint32_t fourcc(const char (&c)[5]) {
  return std::uint32_t(std::uint8_t(c[0])) | std::uint32_t(std::uint8_t(c[1])) << 8 |
         std::uint32_t(std::uint8_t(c[2])) << 16 | std::uint32_t(std::uint8_t(c[3])) << 24;
}
const std::uint32_t kCodecNone = fourcc("NONE"), kCodec16z = fourcc("16zP"), kCodec16zTables = fourcc("16zT"),
                    kCodec8z = fourcc("Im8z"), kCodecJpeg = fourcc("JPEG");
constexpr std::uint32_t kDepthNode = 2, kImageNode = 3, kIrNode = 4;  // XnProductionNodeType

struct Fail {
  std::string what;
  std::uint64_t at;
};

// Bytes per pixel of an OpenNI2 pixel format (oniPixelFormat), 0 for one libOniFile cannot size.
int bytesPerPixel(std::uint64_t format) {
  switch (format) {
    case 100:
    case 101:
    case 102:
    case 103:
      return 2;  // depth 1 mm, 100 um, shifts
    case 200:
      return 3;  // RGB888
    case 201:
    case 205:
      return 2;  // YUV422, YUYV
    case 202:
      return 1;  // gray8
    case 203:
      return 2;  // gray16
    default:
      return 0;  // JPEG (204) and unknown values
  }
}

// The same for OpenNI 1's pixel formats (xnPixelFormat), which recordings made with OpenNI 1 hold
// instead: RGB24, YUV422, gray 8, gray 16 (depth); MJPEG and unknown values 0.
int bytesPerPixelOpenNi1(std::uint64_t format) {
  switch (format) {
    case 1:
      return 3;
    case 2:
      return 2;
    case 3:
      return 1;
    case 4:
      return 2;
    default:
      return 0;
  }
}

// The fields of one record, read in order; every read stays inside them.
class Fields {
 public:
  Fields(const std::vector<std::uint8_t>& bytes, std::uint64_t at) : b_(bytes), at_(at) {}
  template <typename T>
  T get(const char* what) {
    if (b_.size() - pos_ < sizeof(T)) throw Fail{std::string("record fields end inside its ") + what, at_};
    T v;
    std::memcpy(&v, b_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  std::string name(const char* what) {
    const auto n = get<std::uint32_t>(what);
    if (n == 0 || n > kMaxNameBytes) throw Fail{std::string(what) + " of " + std::to_string(n) + " bytes", at_};
    if (b_.size() - pos_ < n) throw Fail{std::string("record fields end inside its ") + what, at_};
    const char* s = reinterpret_cast<const char*>(b_.data() + pos_);
    if (s[n - 1] != '\0' || std::memchr(s, '\0', n - 1))
      throw Fail{std::string(what) + " not a terminated string", at_};
    // One byte past 127 in a name crashes libOniFile where an ASCII change does not (fuzz_oni; most
    // likely its name hash, reading bytes as signed chars). Recorders write printable ASCII names.
    for (std::uint32_t i = 0; i + 1 < n; ++i)
      if (static_cast<unsigned char>(s[i]) < 0x20 || static_cast<unsigned char>(s[i]) > 0x7e)
        throw Fail{std::string(what) + " with a byte that is not printable ASCII", at_};
    pos_ += n;
    return std::string(s, n - 1);
  }
  std::size_t left() const { return b_.size() - pos_; }
  const std::uint8_t* here() const { return b_.data() + pos_; }
  void skip(std::size_t n) { pos_ += n; }

 private:
  const std::vector<std::uint8_t>& b_;
  std::uint64_t at_;
  std::size_t pos_ = 0;
};

struct Node {
  std::string name;
  std::uint32_t type = 0, codec = 0, frames = 0;
  std::uint64_t seek_table = 0;
  bool ready = false, removed = false;
  bool counted_at_data_begin = false;  // format 1.0.0.4: the frame count is in the data-begin record
  // The properties frames are sized by, as last recorded.
  std::uint32_t width = 0, height = 0;
  std::uint64_t pixel_format = 0, pixel_format_1 = 0, frame_bytes = 0, mode_count = 0;
  bool has_mode = false, has_pixel_format = false, has_pixel_format_1 = false, has_frame_bytes = false,
       has_max_depth = false;
  std::uint64_t max_depth = 0;
  std::set<std::uint64_t> frame_records;  // where this node's frames start
};

class Walk {
 public:
  explicit Walk(const std::string& path) : in_(path, std::ios::binary) {
    if (!in_) throw Fail{"cannot be read", 0};
    in_.seekg(0, std::ios::end);
    size_ = static_cast<std::uint64_t>(in_.tellg());
  }

  long run() {
    header();
    std::uint64_t at = 24;
    for (;;) {
      if (at == size_) throw Fail{"ends without its end record (cut short?)", at};
      const std::uint32_t type = record(at);
      if (type == kEnd) break;
    }
    return finish();
  }

 private:
  void read(std::uint64_t at, void* to, std::uint64_t n, const char* what) {
    if (at > size_ || size_ - at < n) throw Fail{std::string(what) + " cut short by the end of the file", at};
    in_.seekg(static_cast<std::streamoff>(at));
    in_.read(static_cast<char*>(to), static_cast<std::streamsize>(n));
    if (!in_) throw Fail{std::string(what) + " could not be read", at};
  }

  void header() {
    std::array<std::uint8_t, 24> h{};
    if (size_ < h.size()) throw Fail{"shorter than the 24-byte file header", 0};
    read(0, h.data(), h.size(), "file header");
    if (std::memcmp(h.data(), "NI10", 4) != 0) throw Fail{"no NI10 file header", 0};
    std::uint16_t maintenance;
    std::uint32_t build;
    std::memcpy(&maintenance, h.data() + 6, 2);
    std::memcpy(&build, h.data() + 8, 4);
    const auto version = std::array<std::uint64_t, 4>{h[4], h[5], maintenance, build};
    if (version < std::array<std::uint64_t, 4>{1, 0, 0, 4} || version > std::array<std::uint64_t, 4>{1, 0, 1, 0})
      throw Fail{"file format " + std::to_string(h[4]) + "." + std::to_string(h[5]) + "." +
                     std::to_string(maintenance) + "." + std::to_string(build) + ", not 1.0.0.4 to 1.0.1.0",
                 4};
    old32_ = version < std::array<std::uint64_t, 4>{1, 0, 1, 0};
    std::memcpy(&max_timestamp_, h.data() + 12, 8);
    std::memcpy(&max_node_, h.data() + 20, 4);
    if (max_node_ > kMaxNodeId)
      throw Fail{"largest node id " + std::to_string(max_node_) + " (at most " + std::to_string(kMaxNodeId) + ")", 20};
  }

  // Checks the record at `at`, moves `at` past it; returns its type.
  std::uint32_t record(std::uint64_t& at) {
    const std::uint64_t start = at;
    const std::uint32_t header_bytes = old32_ ? 24 : 28;
    std::array<std::uint8_t, 28> h{};
    read(at, h.data(), header_bytes, "record header");
    std::uint32_t magic, type, node_id, fields_bytes, payload_bytes;
    std::memcpy(&magic, h.data(), 4);
    std::memcpy(&type, h.data() + 4, 4);
    std::memcpy(&node_id, h.data() + 8, 4);
    std::memcpy(&fields_bytes, h.data() + 12, 4);
    std::memcpy(&payload_bytes, h.data() + 16, 4);
    // The undo position (the record's last 4 or 8 bytes) is followed only when a program seeks
    // backwards, which keyturn never does; it is not checked.
    if (std::memcmp(&magic, "NIR", 4) != 0) throw Fail{"no record here (NIR magic missing)", at};
    const std::string rec = recordName(type);
    if (rec.empty()) throw Fail{"record of unknown type " + std::to_string(type), at};
    if (fields_bytes < header_bytes || fields_bytes > kMaxFieldsBytes)
      throw Fail{rec + " record with " + std::to_string(fields_bytes) + " bytes of fields", at};
    if (std::uint64_t(fields_bytes) + payload_bytes > kRecordBufferBytes)
      throw Fail{rec + " record of " + std::to_string(std::uint64_t(fields_bytes) + payload_bytes) +
                     " bytes, more than OpenNI2's " + std::to_string(kRecordBufferBytes),
                 at};
    if (size_ - at < std::uint64_t(fields_bytes) + payload_bytes)
      throw Fail{rec + " record cut short by the end of the file", at};
    if (type != kEnd && node_id > max_node_)
      throw Fail{rec + " record of node " + std::to_string(node_id) + " past the header's largest id " +
                     std::to_string(max_node_),
                 at};
    fields_.resize(fields_bytes - header_bytes);
    read(at + header_bytes, fields_.data(), fields_.size(), "record fields");
    Fields f(fields_, at);
    const std::uint64_t payload_at = at + fields_bytes;
    records_[start] = type;
    at += std::uint64_t(fields_bytes) + payload_bytes;

    switch (type) {
      case kNodeAdded1004:
      case kNodeAdded1005:
      case kNodeAdded:
        nodeAdded(type, node_id, f, start);
        expectPayload(rec, payload_bytes, 0, start);
        break;
      case kIntProperty:
      case kRealProperty:
      case kStringProperty:
      case kGeneralProperty:
        property(type, live(node_id, rec, start), f, start);
        expectPayload(rec, payload_bytes, 0, start);
        break;
      case kNodeRemoved:
        live(node_id, rec, start).removed = true;
        expectPayload(rec, payload_bytes, 0, start);
        break;
      case kNodeDataBegin: {
        Node& n = live(node_id, rec, start);
        if (!generator(n)) throw Fail{"data begins for node '" + n.name + "', which makes no frames", start};
        const auto frames = f.get<std::uint32_t>("frame count");
        if (n.counted_at_data_begin) n.frames = frames;  // as libOniFile reads such a node
        (void)f.get<std::uint64_t>("largest timestamp");
        data_begun_ = true;
        expectPayload(rec, payload_bytes, 0, start);
        break;
      }
      case kNodeStateReady: {
        Node& n = live(node_id, rec, start);
        if (generator(n) && n.codec == kCodec16zTables && (!n.has_max_depth || n.max_depth == 0 || n.max_depth > 65535))
          throw Fail{"node '" + n.name + "' compressed with depth tables but no largest depth (1 to 65535)", start};
        n.ready = true;
        expectPayload(rec, payload_bytes, 0, start);
        break;
      }
      case kNewData:
        frame(live(node_id, rec, start), f, payload_at, payload_bytes, start);
        break;
      case kSeekTable:
        if (nodes_.find(node_id) == nodes_.end())
          throw Fail{"seek table of node " + std::to_string(node_id) + ", never added", start};
        break;
      case kEnd:
        if (!data_begun_) throw Fail{"end record before any data", start};
        break;
    }
    return type;
  }

  static std::string recordName(std::uint32_t type) {
    switch (type) {
      case kNodeAdded1004:
      case kNodeAdded1005:
      case kNodeAdded:
        return "node-added";
      case kIntProperty:
        return "integer property";
      case kRealProperty:
        return "real property";
      case kStringProperty:
        return "string property";
      case kGeneralProperty:
        return "property";
      case kNodeRemoved:
        return "node-removed";
      case kNodeDataBegin:
        return "data-begin";
      case kNodeStateReady:
        return "state-ready";
      case kNewData:
        return "frame";
      case kEnd:
        return "end";
      case kSeekTable:
        return "seek-table";
      default:
        return "";
    }
  }

  static bool generator(const Node& n) { return n.type == kDepthNode || n.type == kImageNode || n.type == kIrNode; }

  static void expectPayload(const std::string& rec, std::uint32_t bytes, std::uint32_t want, std::uint64_t at) {
    if (bytes != want) throw Fail{rec + " record with a payload of " + std::to_string(bytes) + " bytes", at};
  }

  Node& live(std::uint32_t id, const std::string& rec, std::uint64_t at) {
    auto it = nodes_.find(id);
    if (it == nodes_.end() || it->second.removed)
      throw Fail{rec + " record of node " + std::to_string(id) + ", which is not there", at};
    return it->second;
  }

  void nodeAdded(std::uint32_t type, std::uint32_t id, Fields& f, std::uint64_t at) {
    Node n;
    n.name = f.name("node name");
    n.type = f.get<std::uint32_t>("node type");
    n.codec = f.get<std::uint32_t>("codec");
    n.counted_at_data_begin = type == kNodeAdded1004;
    if (type != kNodeAdded1004) {
      n.frames = f.get<std::uint32_t>("frame count");
      (void)f.get<std::uint64_t>("first timestamp");
      (void)f.get<std::uint64_t>("last timestamp");
    }
    if (type == kNodeAdded)
      n.seek_table = old32_ ? f.get<std::uint32_t>("seek table position") : f.get<std::uint64_t>("seek table position");
    auto old = nodes_.find(id);
    if (old != nodes_.end() && !old->second.removed) throw Fail{"node " + std::to_string(id) + " added twice", at};
    for (const auto& [other_id, other] : nodes_)
      if (other_id != id && !other.removed && other.name == n.name) throw Fail{"two nodes named '" + n.name + "'", at};
    if (generator(n)) {
      const bool depth_codec = n.codec == kCodecNone || n.codec == kCodec16z || n.codec == kCodec16zTables;
      const bool image_codec = n.codec == kCodecNone || n.codec == kCodec8z || n.codec == kCodecJpeg;
      const bool ok = n.type == kImageNode ? image_codec : depth_codec;
      if (!ok)
        throw Fail{"node '" + n.name + "' with codec " + codecName(n.codec) + ", which OpenNI2 cannot decode for it",
                   at};
      if (n.frames > 100000000) throw Fail{"node '" + n.name + "' of " + std::to_string(n.frames) + " frames", at};
    }
    // Removed and added again (a recording's nodes come back after a rewind); fresh state.
    nodes_[id] = std::move(n);
  }

  static std::string codecName(std::uint32_t c) {
    std::string s;
    for (int i = 0; i < 4; ++i) {
      const char ch = static_cast<char>((c >> (8 * i)) & 0xff);
      s += (ch >= 32 && ch < 127) ? ch : '?';
    }
    return "'" + s + "'";
  }

  void property(std::uint32_t type, Node& n, Fields& f, std::uint64_t at) {
    const std::string name = f.name("property name");
    const auto bytes = f.get<std::uint32_t>("property size");
    if (bytes > f.left())
      throw Fail{"property " + name + " of " + std::to_string(bytes) + " bytes, past its record", at};
    const std::uint8_t* data = f.here();
    f.skip(bytes);
    if ((type == kIntProperty || type == kRealProperty) && bytes != 8)
      throw Fail{"property " + name + " of " + std::to_string(bytes) + " bytes, not 8", at};
    if (type == kStringProperty && (bytes == 0 || data[bytes - 1] != '\0'))
      throw Fail{"string property " + name + " not terminated", at};
    std::uint64_t value = 0;
    if (type == kIntProperty) std::memcpy(&value, data, 8);
    auto sized = [&](std::uint32_t want) {
      if (bytes != want)
        throw Fail{"property " + name + " of " + std::to_string(bytes) + " bytes, not " + std::to_string(want), at};
    };
    auto integer = [&] {
      if (type != kIntProperty) throw Fail{"property " + name + " not an integer", at};
    };
    if (name == "xnMapOutputMode") {
      sized(12);
      std::uint32_t w, h;
      std::memcpy(&w, data, 4);
      std::memcpy(&h, data + 4, 4);
      if (w == 0 || h == 0 || w > 4096 || h > 4096)
        throw Fail{"node '" + n.name + "' of " + std::to_string(w) + " x " + std::to_string(h) + " pixels", at};
      n.width = w, n.height = h, n.has_mode = true;
    } else if (name == "oniPixelFormat") {
      integer();
      n.pixel_format = value, n.has_pixel_format = true;
    } else if (name == "xnPixelFormat") {
      integer();
      n.pixel_format_1 = value, n.has_pixel_format_1 = true;
    } else if (name == "oniRequiredFrameSize") {
      integer();
      if (value == 0 || value > kFrameBufferBytes)
        throw Fail{"node '" + n.name + "' of " + std::to_string(value) + "-byte frames", at};
      n.frame_bytes = value, n.has_frame_bytes = true;
    } else if (name == "xnDeviceMaxDepth") {
      integer();
      n.max_depth = value, n.has_max_depth = true;
    } else if (name == "xnSupportedMapOutputModesCount") {
      integer();
      if (value > kMaxModes) throw Fail{"node '" + n.name + "' lists " + std::to_string(value) + " modes", at};
      n.mode_count = value;
    } else if (name == "xnSupportedMapOutputModes") {
      if (type != kGeneralProperty || bytes != n.mode_count * 12)
        throw Fail{"property " + name + " of " + std::to_string(bytes) + " bytes for " + std::to_string(n.mode_count) +
                       " modes",
                   at};
    } else if (name == "xnFOV") {
      sized(16);
    } else if (name == "xnCropping") {
      sized(12);
    } else if (name == "xnSupportedPixelFormats") {
      sized(4);
    } else if (name == "xnRealWorldTranslationData") {
      sized(24);
    }
  }

  void frame(Node& n, Fields& f, std::uint64_t payload_at, std::uint32_t payload_bytes, std::uint64_t at) {
    if (!generator(n)) throw Fail{"frame of node '" + n.name + "', which makes no frames", at};
    if (!n.ready) throw Fail{"frame of node '" + n.name + "' before it is ready", at};
    const auto timestamp = f.get<std::uint64_t>("timestamp");
    const auto number = f.get<std::uint32_t>("frame number");
    if (number == 0 || number > n.frames)
      throw Fail{"frame " + std::to_string(number) + " of node '" + n.name + "', which has " + std::to_string(n.frames),
                 at};
    if (timestamp > max_timestamp_) throw Fail{"frame timestamp past the header's largest", at};
    if (payload_bytes == 0) throw Fail{"empty frame of node '" + n.name + "'", at};
    // OpenNI2 sizes the frame buffers from these; a decoded frame is copied into one whole.
    if (!n.has_mode || (!n.has_pixel_format && !n.has_pixel_format_1))
      throw Fail{"frame of node '" + n.name + "' before its resolution and pixel format", at};
    const int bpp = n.has_pixel_format ? bytesPerPixel(n.pixel_format) : bytesPerPixelOpenNi1(n.pixel_format_1);
    if (bpp == 0)
      throw Fail{"node '" + n.name + "' in pixel format " +
                     std::to_string(n.has_pixel_format ? n.pixel_format : n.pixel_format_1),
                 at};
    if (n.has_pixel_format && ((n.type == kDepthNode) != (n.pixel_format < 200)))
      throw Fail{"node '" + n.name + "' in pixel format " + std::to_string(n.pixel_format) + ", not one of its kind",
                 at};
    const std::uint64_t image_bytes = std::uint64_t(n.width) * n.height * bpp;
    if (image_bytes > kFrameBufferBytes)
      throw Fail{"node '" + n.name + "' of " + std::to_string(image_bytes) + "-byte frames", at};
    if (n.has_frame_bytes && image_bytes != n.frame_bytes)
      throw Fail{"node '" + n.name + "' of " + std::to_string(n.width) + " x " + std::to_string(n.height) +
                     " pixels in " + std::to_string(n.frame_bytes) + "-byte frames",
                 at};
    if (!n.has_frame_bytes) n.frame_bytes = image_bytes;
    if (n.codec == kCodecNone && payload_bytes > n.frame_bytes)
      throw Fail{"uncompressed frame of " + std::to_string(payload_bytes) + " bytes, more than " +
                     std::to_string(n.frame_bytes),
                 at};
    if (n.codec == kCodecJpeg) {
      std::array<std::uint8_t, 2> soi{};
      read(payload_at, soi.data(), 2, "frame");
      if (soi[0] != 0xFF || soi[1] != 0xD8) throw Fail{"JPEG frame that is not a JPEG image", at};
    }
    n.frame_records.insert(at);
    ++frames_;
  }

  long finish() {
    for (const auto& [id, n] : nodes_) {
      if (n.seek_table == 0 || n.frames == 0) continue;
      const std::uint64_t at = n.seek_table;
      auto it = records_.find(at);
      if (it == records_.end() || it->second != kSeekTable)
        throw Fail{"node '" + n.name + "' points to a seek table that is not there", at};
      seekTable(id, n, at);
    }
    return frames_;
  }

  // libOniFile reads the table whole at open (the node's frames + 1 entries) and seeks by it.
  void seekTable(std::uint32_t id, const Node& n, std::uint64_t at) {
    const std::uint32_t header_bytes = old32_ ? 24 : 28;
    std::array<std::uint8_t, 28> h{};
    read(at, h.data(), header_bytes, "seek table");
    std::uint32_t node_id, fields_bytes, payload_bytes;
    std::memcpy(&node_id, h.data() + 8, 4);
    std::memcpy(&fields_bytes, h.data() + 12, 4);
    std::memcpy(&payload_bytes, h.data() + 16, 4);
    const std::uint32_t entry = old32_ ? 16 : 20;
    if (node_id != id || std::uint64_t(payload_bytes) != (std::uint64_t(n.frames) + 1) * entry)
      throw Fail{"seek table of " + std::to_string(payload_bytes) + " bytes for node '" + n.name + "' of " +
                     std::to_string(n.frames) + " frames",
                 at};
    std::vector<std::uint8_t> table(payload_bytes);
    read(at + fields_bytes, table.data(), table.size(), "seek table");
    for (std::uint32_t k = 1; k <= n.frames; ++k) {
      std::uint64_t pos = 0;
      if (old32_) {
        std::uint32_t p;
        std::memcpy(&p, table.data() + k * entry + 12, 4);
        pos = p;
      } else {
        std::memcpy(&pos, table.data() + k * entry + 12, 8);
      }
      if (!n.frame_records.count(pos))
        throw Fail{"seek table entry " + std::to_string(k) + " of node '" + n.name + "' not one of its frames", at};
    }
  }

  std::ifstream in_;
  std::uint64_t size_ = 0, max_timestamp_ = 0;
  std::uint32_t max_node_ = 0;
  bool old32_ = false, data_begun_ = false;
  std::vector<std::uint8_t> fields_;
  std::map<std::uint32_t, Node> nodes_;
  std::map<std::uint64_t, std::uint32_t> records_;  // every record's start and type
  long frames_ = 0;
};

}  // namespace

long checkOniRecording(const std::string& path) {
  try {
    return Walk(path).run();
  } catch (const Fail& f) {
    throw Error(path + ": not a readable .oni recording (at byte " + std::to_string(f.at) + ": " + f.what + ")");
  }
}

}  // namespace keyturn::drivers
