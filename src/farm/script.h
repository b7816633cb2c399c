#pragma once
// How user text goes into a batch script (farm.cpp writes them, local.cpp reads their
// directives): every string is a shell word, an escaped comment, or a directive value that
// sbatch reads back exactly, else refused. docs/farm.md, "What reaches a batch script".
#include <string>
#include <string_view>

namespace glint::farm::detail {

/// `text` for a `# ...` comment line: control characters as C escapes (\n, \r, \t, \xNN)
/// and backslashes doubled, so the comment stays one line and says what was there.
std::string commentText(std::string_view text);

/// `word` as one bash word on one line: shellWord's quoting, or bash's $'...' with C escapes
/// when it holds control characters (a line break in a file name stays "\n" in the script).
std::string scriptWord(std::string_view word);

/// `value` as the value of an `#SBATCH --option=VALUE` line, written so that sbatch's
/// directive parser reads `value` back: unchanged when made of safe characters, else in
/// single quotes (sbatch, like the shell, ends the line at a line break and takes `#` as
/// a comment outside quotes). Error(Usage) naming `what` for a value no directive can
/// hold: control characters (a line break ends the directive block), a backslash (sbatch
/// then leaves Slurm's filename patterns unexpanded).
std::string directiveValue(std::string_view value, std::string_view what);

/// `directory`/`file` for `#SBATCH --output`: the directory checked as directiveValue does
/// and its `%` doubled (sbatch expands %j, %a, ...), `file` kept as a pattern ("piece-%a.log").
std::string outputPattern(std::string_view directory, std::string_view file, std::string_view what);

}  // namespace glint::farm::detail
