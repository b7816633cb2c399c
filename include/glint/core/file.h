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
// A run with several outputs writes all of them or none: while an OutputSet is open (every
// ToolRun opens one, core/tool.h), the files written through this header are staged — each
// complete in its temporary — and renamed into place together by OutputSet::commit(), which
// ToolRun::finish() calls after the last output. A run that fails or is interrupted before
// then (a full disk at its third output, an error, Ctrl-C) removes its temporaries: every
// existing output is left as it was. A write that fails for want of space says so: "cannot
// write 'x.png': no space left on device".
//
/// ```cpp
/// #include <fstream>
/// glint::writeAtomically("out.txt", [&](const std::filesystem::path& tmp) {
///   std::ofstream(tmp) << "complete or absent\n";  // tmp keeps the extension, so format detection works
/// });
/// ```

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace glint {

/// When a file written atomically is renamed into place.
enum class Commit {
  WithRun,  ///< with the open OutputSet's other files (at once when none is open): outputs
  Now       ///< at once: files the run itself reads back (caches)
};

/// Calls write(tmp) with a temporary path next to `destination` (same extension),
/// then renames it to `destination` (staged in the open OutputSet, if any: see above).
/// Throws Error(Output) with a one-line reason when the directory does not exist or is
/// not writable, or the filesystem is full; removes the temporary file if `write`
/// throws, and rethrows.
void writeAtomically(const std::filesystem::path& destination,
                     const std::function<void(const std::filesystem::path& tmp)>& write, Commit when = Commit::WithRun);

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

/// A run's outputs, committed together (see the top of this header). Opening one makes it
/// the set the writes above stage into, until it is destroyed (sets nest: the innermost
/// open one receives the writes). Thread-safe: outputs written in parallel stage into one set.
///
/// ```cpp
/// {
///   glint::OutputSet outputs;
///   glint::writeTextAtomically("a.txt", "first\n");   // staged: a.txt is not touched yet
///   glint::writeTextAtomically("b.txt", "second\n");
///   outputs.commit();                                // both renamed into place now
/// }  // without commit(): both temporaries removed, a.txt and b.txt as they were
/// ```
class OutputSet {
public:
  OutputSet();
  /// Removes the temporaries of everything not committed.
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  /// Renames every staged file into place. When a rename fails, the files already renamed
  /// are put back as they were (the previous ones were kept as hard links until then) and
  /// Error(Output) names the file. Files staged after a commit wait for the next one.
  void commit();
  /// Removes every staged temporary now.
  void discard();
  /// Whether a file for `destination` is staged (by its absolute, normalized path).
  bool staged(const std::filesystem::path& destination) const;
  /// Commits `destination`'s staged file under `other` instead (a partial video written
  /// beside a complete one). Error(Internal) when nothing is staged for `destination`.
  void redirect(const std::filesystem::path& destination, const std::filesystem::path& other);

  struct Impl;

private:
  std::unique_ptr<Impl> m_impl;
};

/// Creates `dir` and the folders above it that are missing (Error(Output), one line, when it
/// cannot). Inside an open OutputSet the folders it made belong to the run: a run that fails
/// or is interrupted removes them again with its temporaries (where they are empty), so a
/// failed run leaves no empty folder behind; a committed run keeps them.
void createOutputDirectories(const std::filesystem::path& dir);

/// The one-line reason a write to `destination` failed: "no space left on device (12 KiB
/// free)" when its filesystem is full (or `error` is ENOSPC), else strerror(error).
std::string writeFailure(const std::filesystem::path& destination, int error);

/// `stem + tail` as a file name that fits the limit of names in `dir` (NAME_MAX, 255 bytes
/// on most filesystems) with `reserved` bytes to spare: the stem is shortened, at the start
/// of a UTF-8 character, and `tail` (a suffix and an extension) kept whole where it fits.
/// The temporaries beside an output and a partial video's name are made with it, so every
/// output name the filesystem accepts can be written.
std::string fitFileName(const std::filesystem::path& dir, std::string stem, std::string_view tail, std::size_t reserved = 0);

/// A path's extension in ASCII lower case, with its dot: "Model.GLB" → ".glb", "a" → "".
/// What every format decision by file name compares (image, mesh, video and asset names).
std::string lowerExtension(const std::filesystem::path& path);

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
