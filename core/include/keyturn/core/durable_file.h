#pragma once
// Files that survive a crash or a power cut whole or not at all: written to a
// temporary name, flushed to disk, renamed into place, and the folder synced.
// Every file keyturn writes goes through here (clouds, datasets, caches, models, reports).
#include <functional>
#include <string>
#include <vector>

namespace keyturn {

void writeFileDurably(const std::string& path, const std::string& bytes);
// The same for a library that writes by file name (PCL, an image encoder): `fill` writes the
// temporary it is given, PATH.tmp.XXXXXX followed by PATH's extension (an encoder picks its format
// from it), which is then flushed and renamed into place; removed again when anything fails.
void writeFileDurablyWith(const std::string& path, const std::function<void(const std::string& tmp)>& fill);
// Whether a file name is one of those temporaries (NAME.tmp.XXXXXX, NAME.tmp.XXXXXX.EXT, and the
// fixed NAME.pcd.tmp / NAME.tmp.png of keyturn before 2026-12): what a process killed mid-write
// leaves behind. Nothing else keyturn writes is named so.
bool isInterruptedWriteTemporary(const std::string& file_name);
// Removes such leftovers in `dir` and its subfolders, except under the folders named in `skip`
// (relative to dir: another process's writes still running); returns how many were removed.
std::size_t removeInterruptedWriteTemporaries(const std::string& dir, const std::vector<std::string>& skip = {});
// Makes an already written file durable under its final name (fsync, rename, fsync dir).
void commitFile(const std::string& tmp_path, const std::string& final_path);
// Appends one line and syncs; the line is either wholly in the file or not at all
// as far as readers that ignore an unterminated last line are concerned.
void appendLineDurably(const std::string& path, const std::string& line);
void syncDirectory(const std::string& dir);
// Flushes a file another library wrote (a classifier's weights) to disk.
void syncFile(const std::string& path);

}  // namespace keyturn
