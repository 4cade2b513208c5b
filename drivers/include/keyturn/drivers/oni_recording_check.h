#pragma once
// Checks an OpenNI2 .oni recording's container before OpenNI2 reads it. Debian's libOniFile trusts
// the file: a record whose sizes, node ids or property values a corrupt file got wrong makes it
// read and write past its buffers and crash the program (issue 52: 20 random bytes changed in a
// recording's first 4 KB crashed `keyturn grab` in 7 of 12 files). No OpenNI2 call can be
// guarded against that, so the file is walked here first, record by record, as libOniFile will
// walk it, and refused in one line when anything it would trust is out of bounds.
//
// What is checked: the file header (magic, a format version libOniFile reads, the node count);
// every record up to the end record: magic, a known type, a node that was added, its fields and
// payload inside the file and inside libOniFile's record buffer; each record's fields (names of
// printable ASCII terminated within the record, value sizes); the properties libOniFile and OpenNI2
// size frames and buffers by (resolution, pixel format, frame size, mode lists) against each other;
// each node's codec; each frame's number, timestamp and payload size (at most one frame for an
// uncompressed stream, non-empty and within libOniFile's buffer for a compressed one, a JPEG image
// for JPEG); each seek table (where its node points, its size, every entry a frame of that node).
// What is not: the compressed content of a frame (libOniFile's decoders bound their output; 1,200
// mutated recordings never crashed it there, docs/reliability.md), nor undo positions, which only a
// program seeking backwards follows.
#include <string>

namespace keyturn::drivers {

// Throws keyturn::Error "PATH: not a readable .oni recording (at byte N: WHAT)" when the recording
// cannot be played safely; returns the number of frames it holds (all streams) otherwise.
long checkOniRecording(const std::string& path);

}  // namespace keyturn::drivers
