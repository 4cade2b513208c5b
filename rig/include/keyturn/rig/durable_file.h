#pragma once
// Files that survive a crash or a power cut whole or not at all: written to a
// temporary name, flushed to disk, renamed into place, and the folder synced.
#include <string>

namespace keyturn::rig {

void writeFileDurably(const std::string& path, const std::string& bytes);
// Makes an already written file durable under its final name (fsync, rename, fsync dir).
void commitFile(const std::string& tmp_path, const std::string& final_path);
// Appends one line and syncs; the line is either wholly in the file or not at all
// as far as readers that ignore an unterminated last line are concerned.
void appendLineDurably(const std::string& path, const std::string& line);
void syncDirectory(const std::string& dir);
std::string sha256File(const std::string& path);  // lowercase hex; throws keyturn::Error

}  // namespace keyturn::rig
