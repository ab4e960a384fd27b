// Output files that are never half-written.
#ifndef DYNSLAM_FILE_IO_H_
#define DYNSLAM_FILE_IO_H_

#include <string>
#include <string_view>

#include "dynslam/status.h"

namespace dynslam {

// Writes `contents` to PATH.partial beside `path`, flushes it to disk and renames it to `path`,
// so that `path` is either its old file or the complete new one, whatever interrupts the write.
// A failure (disk full, file-size limit, permission) removes PATH.partial and returns an Error
// naming `path` and the system's reason. A kill during the write can leave PATH.partial behind;
// its name says it is incomplete.
// Under a file-size limit the system sends SIGXFSZ, which ends a process by default; a program
// that wants the error instead ignores SIGXFSZ (the command line does).
Status WriteFileAtomically(const std::string& path, std::string_view contents);

// Removes `path` when it exists: an error only when it exists and cannot be removed.
Status RemoveIfPresent(const std::string& path);

}  // namespace dynslam

#endif  // DYNSLAM_FILE_IO_H_
