#pragma once
// Files that survive a crash or a power cut whole or not at all: written to a
// temporary name, flushed to disk, renamed into place, and the folder synced.
// Every file keyturn writes goes through here (clouds, datasets, caches, models, reports).
#include <string>

namespace keyturn {

void writeFileDurably(const std::string& path, const std::string& bytes);
// Makes an already written file durable under its final name (fsync, rename, fsync dir).
void commitFile(const std::string& tmp_path, const std::string& final_path);
// Appends one line and syncs; the line is either wholly in the file or not at all
// as far as readers that ignore an unterminated last line are concerned.
void appendLineDurably(const std::string& path, const std::string& line);
void syncDirectory(const std::string& dir);
// Flushes a file another library wrote (a classifier's weights) to disk.
void syncFile(const std::string& path);

}  // namespace keyturn
