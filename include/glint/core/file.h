#pragma once
// glint/core/file.h — file helpers: atomic writes, whole-file reads.
//
// Outputs are written atomically: to a temporary file in the destination's
// directory, then renamed over the destination. A crash, an exception or
// Ctrl-C never leaves a partial file under the final name, and an existing
// file is replaced only by a complete one. A process killed outright (kill -9)
// leaves its temporary, named ".<stem>.tmp<pid>-<n><ext>"; the next write into that
// directory removes such files whose process is gone.
//
/// ```cpp
/// #include <fstream>
/// glint::writeAtomically("out.txt", [&](const std::filesystem::path& tmp) {
///   std::ofstream(tmp) << "complete or absent\n";  // tmp keeps the extension, so format detection works
/// });
/// ```

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace glint {

/// Calls write(tmp) with a temporary path next to `destination` (same extension),
/// then renames it to `destination`. Throws Error(Output) with a one-line reason
/// when the directory does not exist or is not writable; removes the temporary
/// file if `write` throws, and rethrows.
void writeAtomically(const std::filesystem::path& destination,
                     const std::function<void(const std::filesystem::path& tmp)>& write);

/// The same for output produced over time (a video encoded frame by frame): write to
/// temporary(), then commit() renames it to the destination. Destroyed without commit(),
/// it removes the temporary file. Error(Output) from the constructor as checkWritable.
///
/// ```cpp
/// #include <fstream>
/// glint::AtomicFile file("log.txt");
/// std::ofstream out(file.temporary());
/// for (int frame = 0; frame < 3; ++frame) out << "frame " << frame << "\n";
/// out.close();
/// file.commit();  // without it, the destructor removes the temporary
/// ```
class AtomicFile {
public:
  explicit AtomicFile(const std::filesystem::path& destination);
  ~AtomicFile();
  AtomicFile(AtomicFile&& other) noexcept;
  AtomicFile& operator=(AtomicFile&&) = delete;
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::filesystem::path& temporary() const { return m_temporary; }
  const std::filesystem::path& destination() const { return m_destination; }
  /// Renames the temporary file to the destination. Error(Output) when that fails.
  void commit();

private:
  std::filesystem::path m_destination, m_temporary;
  bool m_committed = false;
};

/// Writes `contents` to `destination` atomically.
void writeTextAtomically(const std::filesystem::path& destination, std::string_view contents);

/// Reads a whole file; Error(Input) naming the file when it cannot be read.
std::string readTextFile(const std::filesystem::path& path);

/// A file a command reads or writes, with the name a message gives it: "the input",
/// "-o", "--json", "--ao".
struct FileUse {
  std::filesystem::path path;
  std::string role;
};

/// The promise that a command never destroys its own files, checked before any work:
/// Error(Usage) when an output is one of the inputs, or two outputs are one file. Files are
/// compared by identity (device and inode), so hard links, symbolic links and spellings such
/// as "./a.png" or "dir/../a.png" count; outputs that do not exist yet are compared by their
/// absolute, normalized path. Empty paths and "-" (stdin, stdout) are skipped.
///
/// ```cpp
/// try {
///   glint::checkDistinctFiles({{"clip.mp4", "the input"}}, {{"./clip.mp4", "-o"}});
/// } catch (const glint::Error& e) {
///   // "-o './clip.mp4' is the input 'clip.mp4': writing it would destroy the input; choose another name"
/// }
/// ```
void checkDistinctFiles(const std::vector<FileUse>& inputs, const std::vector<FileUse>& outputs);

/// Throws Error(Output) when `destination` could not be created: its directory is
/// missing or not writable. Lets a long command fail before it starts working.
void checkWritable(const std::filesystem::path& destination);

}  // namespace glint
