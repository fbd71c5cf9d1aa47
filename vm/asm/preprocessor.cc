// The preprocessor's directives and macro expansion; the text's logical lines, its tokens and the
// #if expressions have files of their own (vm/asm/preprocessor_lines.h, preprocessor_tokens.h,
// preprocessor_expression.h).
#include "vm/asm/preprocessor.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <exception>
#include <iterator>
#include <limits>
#include <memory>
#include <set>
#include <unordered_map>

#include "vm/asm/preprocessor_expression.h"
#include "vm/asm/preprocessor_lines.h"
#include "vm/asm/preprocessor_tokens.h"
#include "vm/core/input_file.h"

namespace vs11 {
namespace {

using namespace preprocessing;  // NOLINT: this file is the preprocessor those names serve

// Hostile input must not exhaust the stack, whatever the options say.
constexpr int kMaxExpansionDepth = 128;   // macro arguments pre-expanded inside macro arguments
constexpr int kMaxIncludeDepthCap = 200;  // each #include level is a few stack frames
// Macro expansion and #include are charged "work" against max_output_bytes, so that expansions
// that produce nothing, or whose output is never emitted, are bounded as well. A token costs more
// than its text because its memory and handling do; the slack lets small limits expand small files.
constexpr std::size_t kTokenWork = 64;
constexpr std::size_t kWorkSlack = std::size_t{64} << 10;

struct Macro {
  int id = 0;    // the same for every definition of one name
  HideSet self;  // {id}, kept to avoid building it for each use
  bool function_like = false;
  std::vector<std::string> params;
  std::vector<Token> body;  // spaces inside collapsed to one, none at either end
};

class Preprocessor {
 public:
  Preprocessor(const PreprocessOptions& options, const FileReader& reader) : options_(options), reader_(reader) {
    std::size_t max = std::numeric_limits<std::size_t>::max();
    work_limit_ = options.max_output_bytes > max - kWorkSlack ? max : options.max_output_bytes + kWorkSlack;
  }
  PreprocessResult Run(std::string_view text, const std::string& file_name);

 private:
  struct Conditional {
    SourceLoc loc;
    std::string directive;  // if, ifdef or ifndef, for the unterminated message
    bool parent_active = true;
    bool taken = false;   // a branch has been chosen, so later #elif/#else are skipped
    bool active = false;  // lines of the current branch are kept
    bool seen_else = false;
  };
  struct FileState {
    std::filesystem::path path;  // where it was found: #include "..." looks beside it
    std::string name;            // reported name, which #line may change
    int line_offset = 0;         // added to physical line numbers by #line
    std::vector<Conditional> conditionals;
  };
  using Args = std::vector<std::vector<Token>>;

  SourceLoc Loc(int column) const { return {file_->name, ReportedLine(), column}; }
  int ReportedLine() const { return line_->line + file_->line_offset; }
  void Error(int column, DiagnosticCode code, std::string message) {
    result_.diagnostics.Error(Loc(column), code, std::move(message));
  }
  bool Active() const { return file_->conditionals.empty() || file_->conditionals.back().active; }
  bool IsDefined(const std::string& name) const { return macros_.count(name) != 0; }
  bool ChargeWork(std::size_t units, int column);
  const Token* ExpectName(const std::vector<Token>& rest, const char* directive, int column);

  void ProcessFile(std::string_view text, FileState* file, int depth);
  void ProcessLine(const LogicalLine& line, int depth);
  void EmitLine(const std::vector<Token>& tokens);
  void HandleDirective(const std::vector<Token>& tokens, std::size_t hash, int depth);
  void HandleConditional(const std::string& directive, int column, const std::vector<Token>& rest);
  bool EvaluateCondition(const std::vector<Token>& rest, int column);
  bool ReplaceDefined(const std::vector<Token>& rest, std::vector<Token>* out);
  void HandleDefine(const std::vector<Token>& rest, int column);
  bool ParseParameters(const std::vector<Token>& rest, std::size_t* i, int column, Macro* macro);
  void HandleInclude(const std::vector<Token>& rest, int column, int depth);
  void HandleLine(const std::vector<Token>& rest, int column);

  std::vector<Token> Expand(std::vector<Token> input, int depth);
  bool ReplaceMacro(const Macro& macro, const Token& name, std::vector<Token>* pending, int depth,
                    std::vector<Token>* out);
  bool CollectArguments(const Macro& macro, const Token& name, const std::vector<Token>& pending, Args* args,
                        std::size_t* rparen);
  bool CheckArgumentCount(const Macro& macro, const Token& name, Args* args);
  std::vector<Token> Substitute(const Macro& macro, const Args& args, int depth);

  const PreprocessOptions& options_;
  const FileReader& reader_;
  PreprocessResult result_;
  std::unordered_map<std::string, Macro> macros_;
  std::unordered_map<std::string, int> macro_ids_;  // hide sets hold small ids rather than names
  std::set<std::string> pragma_once_;               // lexically normal paths of #pragma once files
  FileState* file_ = nullptr;                       // the file and line being processed
  const LogicalLine* line_ = nullptr;
  std::size_t output_bytes_ = 0;
  std::size_t work_ = 0;  // expansion and inclusion work, bounded so nothing can run away
  std::size_t work_limit_ = 0;
  bool stopped_ = false;  // a limit was hit: the rest of the input is ignored
};

bool Preprocessor::ChargeWork(std::size_t units, int column) {
  work_ += units;
  if (work_ > work_limit_ && !stopped_) {
    Error(column, DiagnosticCode::kExpansionLimit,
          fmt::format("macro or #include expansion exceeds the output limit of {} bytes", options_.max_output_bytes));
    stopped_ = true;
  }
  return !stopped_;
}

const Token* Preprocessor::ExpectName(const std::vector<Token>& rest, const char* directive, int column) {
  std::size_t i = NextNonSpace(rest, 0);
  if (i < rest.size() && rest[i].kind == TokenKind::kIdentifier) return &rest[i];
  Error(ColumnAt(rest, i, column), DiagnosticCode::kMacroDefinition, fmt::format("#{} needs a macro name", directive));
  return nullptr;
}

PreprocessResult Preprocessor::Run(std::string_view text, const std::string& file_name) {
  // Command-line definitions go through the #define parser, so "F(x)" names work too.
  FileState command_line{"", "<command line>", 0, {}};
  LogicalLine no_line;
  file_ = &command_line;
  line_ = &no_line;
  for (const auto& [name, value] : options_.defines) HandleDefine(Tokenize(name + " " + value, nullptr), 0);
  FileState main_file{file_name, file_name, 0, {}};
  ProcessFile(text, &main_file, 0);
  return std::move(result_);
}

void Preprocessor::ProcessFile(std::string_view text, FileState* file, int depth) {
  LineSplitter splitter(text);
  LogicalLine line;
  while (!stopped_ && splitter.Next(&line)) {
    file_ = file;  // an #include on the previous line pointed these elsewhere
    line_ = &line;
    ProcessLine(line, depth);
  }
  if (stopped_) return;
  if (splitter.in_comment()) {
    result_.diagnostics.Error({file->name, splitter.comment_line() + file->line_offset, splitter.comment_column()},
                              DiagnosticCode::kUnterminatedComment, "unterminated /* comment");
  }
  for (const Conditional& conditional : file->conditionals) {
    result_.diagnostics.Error(conditional.loc, DiagnosticCode::kUnbalancedConditional,
                              fmt::format("unterminated #{}", conditional.directive));
  }
}

void Preprocessor::ProcessLine(const LogicalLine& line, int depth) {
  std::vector<Token> tokens = Tokenize(line.text, &line.columns);
  std::size_t first = NextNonSpace(tokens, 0);
  if (first < tokens.size() && tokens[first].kind == TokenKind::kPunctuator && tokens[first].text[0] == '#') {
    HandleDirective(tokens, first, depth);
  } else if (Active()) {
    EmitLine(Expand(std::move(tokens), 0));
  }
}

void Preprocessor::EmitLine(const std::vector<Token>& tokens) {
  if (stopped_) return;
  PreprocessedLine out{"", file_->name, ReportedLine(), {}};
  for (const Token& token : tokens) {
    out.text += token.text;
    for (std::size_t i = 0; i < token.text.size(); ++i) {
      out.columns.push_back(token.offset >= 0 ? line_->columns[token.offset + i] : token.column);
    }
  }
  std::size_t begin = 0, end = out.text.size();
  while (end > 0 && IsSpace(out.text[end - 1])) --end;
  while (begin < end && IsSpace(out.text[begin])) ++begin;
  if (begin == end) return;
  out.text = out.text.substr(begin, end - begin);
  out.columns = std::vector<int>(out.columns.begin() + begin, out.columns.begin() + end);
  output_bytes_ += out.text.size() + 1;
  if (output_bytes_ > options_.max_output_bytes) {
    Error(out.columns[0], DiagnosticCode::kExpansionLimit,
          fmt::format("preprocessed output exceeds the limit of {} bytes", options_.max_output_bytes));
    stopped_ = true;
    return;
  }
  result_.lines.push_back(std::move(out));
}

void Preprocessor::HandleDirective(const std::vector<Token>& tokens, std::size_t hash, int depth) {
  int column = tokens[hash].column;
  std::size_t name_index = NextNonSpace(tokens, hash + 1);
  if (tokens[hash].text != "#") {
    if (Active()) Error(column, DiagnosticCode::kUnknownDirective,
                        fmt::format("invalid directive '{}'", tokens[hash].text));
    return;
  }
  if (name_index == tokens.size()) return;  // a lone '#' is the null directive
  const Token& name = tokens[name_index];
  const std::vector<Token> rest(tokens.begin() + name_index + 1, tokens.end());
  const std::string directive = name.kind == TokenKind::kIdentifier ? name.text : "";
  if (directive == "if" || directive == "ifdef" || directive == "ifndef" || directive == "elif" ||
      directive == "else" || directive == "endif") {
    HandleConditional(directive, column, rest);
  } else if (!Active()) {
    return;  // skipped text may hold anything, even unknown directives
  } else if (directive == "define") {
    HandleDefine(rest, column);
  } else if (directive == "undef") {
    if (const Token* macro = ExpectName(rest, "undef", column)) macros_.erase(macro->text);
  } else if (directive == "include") {
    HandleInclude(rest, column, depth);
  } else if (directive == "line") {
    HandleLine(rest, column);
  } else if (directive == "error" || directive == "warning") {
    std::vector<Token> words = rest;
    TrimSpaces(&words);
    std::string message = "#" + directive + (words.empty() ? "" : " ");
    for (const Token& token : words) message += token.text;
    if (directive == "error") Error(column, DiagnosticCode::kErrorDirective, message);
    if (directive == "warning") result_.diagnostics.Warning(Loc(column), DiagnosticCode::kWarningDirective, message);
  } else if (directive == "pragma") {
    std::size_t i = NextNonSpace(rest, 0);
    if (i < rest.size() && rest[i].text == "once") pragma_once_.insert(file_->path.lexically_normal().string());
  } else {
    Error(name.column, DiagnosticCode::kUnknownDirective, fmt::format("unknown directive '#{}'", name.text));
  }
}

void Preprocessor::HandleConditional(const std::string& directive, int column, const std::vector<Token>& rest) {
  std::vector<Conditional>& stack = file_->conditionals;
  if (directive == "if" || directive == "ifdef" || directive == "ifndef") {
    bool parent_active = Active();
    bool value = false;
    if (parent_active && directive == "if") {
      value = EvaluateCondition(rest, column);
    } else if (parent_active) {
      const Token* name = ExpectName(rest, directive.c_str(), column);
      value = name != nullptr && IsDefined(name->text) == (directive == "ifdef");
    }
    stack.push_back({Loc(column), directive, parent_active, value, value, false});
    return;
  }
  if (stack.empty()) {
    Error(column, DiagnosticCode::kUnbalancedConditional, fmt::format("#{} without #if", directive));
    return;
  }
  Conditional& top = stack.back();
  if (directive == "endif") {
    stack.pop_back();
  } else if (top.seen_else) {
    Error(column, DiagnosticCode::kUnbalancedConditional, fmt::format("#{} after #else", directive));
    top.active = false;
  } else if (directive == "else") {
    top.seen_else = true;
    top.active = top.parent_active && !top.taken;
    top.taken = true;
  } else {  // #elif is evaluated only when no earlier branch was taken
    top.active = top.parent_active && !top.taken && EvaluateCondition(rest, column);
    top.taken = top.taken || top.active;
  }
}

bool Preprocessor::EvaluateCondition(const std::vector<Token>& rest, int column) {
  std::vector<Token> replaced;
  if (!ReplaceDefined(rest, &replaced)) return false;
  std::vector<Token> significant;
  for (Token& token : Expand(std::move(replaced), 0)) {
    if (token.kind != TokenKind::kSpace) significant.push_back(std::move(token));
  }
  const Result<std::int64_t> value = EvaluateExpression(std::move(significant), column);
  if (!value) {
    Error(value.error().loc.column, value.error().code, value.message());
    return false;
  }
  return *value != 0;
}

// `defined X` must be answered before expansion, or X would be replaced by its body.
bool Preprocessor::ReplaceDefined(const std::vector<Token>& rest, std::vector<Token>* out) {
  for (std::size_t i = 0; i < rest.size(); ++i) {
    out->push_back(rest[i]);
    if (rest[i].kind != TokenKind::kIdentifier || rest[i].text != "defined") continue;
    std::size_t j = NextNonSpace(rest, i + 1);
    bool parenthesised = j < rest.size() && IsPunct(rest[j], "(");
    if (parenthesised) j = NextNonSpace(rest, j + 1);
    std::size_t end = parenthesised ? NextNonSpace(rest, j + 1) : j;
    if (j >= rest.size() || rest[j].kind != TokenKind::kIdentifier ||
        (parenthesised && (end >= rest.size() || !IsPunct(rest[end], ")")))) {
      Error(rest[i].column, DiagnosticCode::kConditionExpression, "'defined' needs a macro name, or (name)");
      return false;
    }
    out->back().kind = TokenKind::kNumber;
    out->back().text = std::string(1, IsDefined(rest[j].text) ? '1' : '0');
    i = end;
  }
  return true;
}

void Preprocessor::HandleDefine(const std::vector<Token>& rest, int column) {
  const Token* name = ExpectName(rest, "define", column);
  if (name == nullptr) return;
  if (name->text == "defined") {
    Error(name->column, DiagnosticCode::kMacroDefinition, "'defined' cannot be used as a macro name");
    return;
  }
  if (macro_ids_.size() >= options_.max_macros && macro_ids_.count(name->text) == 0) {
    Error(name->column, DiagnosticCode::kTooManyMacros,
          fmt::format("more than {} macros defined; a vs_1_1 program needs a few tens", options_.max_macros));
    stopped_ = true;
    return;
  }
  Macro macro;
  macro.id = macro_ids_.emplace(name->text, static_cast<int>(macro_ids_.size())).first->second;
  macro.self = std::make_shared<const std::vector<int>>(1, macro.id);
  std::size_t i = static_cast<std::size_t>(name - rest.data()) + 1;
  // Only a '(' touching the name makes a function-like macro: "#define N (1)" is object-like.
  if (i < rest.size() && IsPunct(rest[i], "(")) {
    macro.function_like = true;
    if (!ParseParameters(rest, &i, column, &macro)) return;
  }
  std::vector<Token> body(rest.begin() + i, rest.end());
  TrimSpaces(&body);
  for (Token& token : body) {
    token.offset = -1;
    if (token.kind != TokenKind::kSpace) {
      macro.body.push_back(std::move(token));
    } else if (macro.body.back().kind != TokenKind::kSpace) {  // trimmed: never first
      macro.body.push_back(MakeToken(TokenKind::kSpace, " "));
    }
  }
  if (!macro.body.empty() && (IsPunct(macro.body.front(), "##") || IsPunct(macro.body.back(), "##"))) {
    Error(name->column, DiagnosticCode::kMacroDefinition, "'##' cannot appear at either end of a macro body");
    return;
  }
  macros_[name->text] = std::move(macro);
}

// Parses "(a, b)" starting at the '(' at *i; leaves *i after the ')'.
bool Preprocessor::ParseParameters(const std::vector<Token>& rest, std::size_t* i, int column, Macro* macro) {
  std::size_t j = NextNonSpace(rest, *i + 1);
  bool more = j >= rest.size() || !IsPunct(rest[j], ")");
  while (more) {
    std::vector<std::string>& params = macro->params;
    if (j >= rest.size() || rest[j].kind != TokenKind::kIdentifier) {
      Error(ColumnAt(rest, j, column), DiagnosticCode::kMacroDefinition, "expected a parameter name in #define");
      return false;
    } else if (std::find(params.begin(), params.end(), rest[j].text) != params.end()) {
      Error(rest[j].column, DiagnosticCode::kMacroDefinition,
            fmt::format("duplicate macro parameter '{}'", rest[j].text));
      return false;
    } else {
      params.push_back(rest[j].text);
    }
    j = NextNonSpace(rest, j + 1);
    more = j < rest.size() && IsPunct(rest[j], ",");
    if (!more && (j >= rest.size() || !IsPunct(rest[j], ")"))) {
      Error(ColumnAt(rest, j, column), DiagnosticCode::kMacroDefinition, "expected ',' or ')' in macro parameter list");
      return false;
    }
    if (more) j = NextNonSpace(rest, j + 1);
  }
  *i = j + 1;
  return true;
}

// Reads "file" or <file>; `quoted` tells which, since only "file" looks beside the includer.
bool ParseIncludeName(const std::vector<Token>& tokens, std::string* name, bool* quoted) {
  std::size_t i = NextNonSpace(tokens, 0);
  if (i == tokens.size()) return false;
  const std::string& text = tokens[i].text;
  *quoted = tokens[i].kind == TokenKind::kString;
  if (*quoted) {
    *name = text.size() >= 2 && text.back() == '"' ? text.substr(1, text.size() - 2) : "";
    return !name->empty();
  }
  if (!IsPunct(tokens[i], "<")) return false;
  name->clear();
  for (++i; i < tokens.size() && !IsPunct(tokens[i], ">"); ++i) *name += tokens[i].text;
  return i < tokens.size() && !name->empty();
}

void Preprocessor::HandleInclude(const std::vector<Token>& rest, int column, int depth) {
  std::string name;
  bool quoted = false;
  if (!ParseIncludeName(rest, &name, &quoted) && !ParseIncludeName(Expand(rest, 0), &name, &quoted)) {
    Error(column, DiagnosticCode::kMalformedDirective, "#include expects \"file\" or <file>");
    return;
  }
  int max_depth = std::min(options_.max_include_depth, kMaxIncludeDepthCap);
  if (depth + 1 > max_depth) {
    // Nearly always a cycle; going on would repeat the same error at every level.
    Error(column, DiagnosticCode::kIncludeTooDeep,
          fmt::format("#include nested more than {} levels deep (include cycle?)", max_depth));
    stopped_ = true;
    return;
  }
  std::replace(name.begin(), name.end(), '\\', '/');  // DX8 shaders were written on Windows
  std::vector<std::filesystem::path> candidates;
  if (quoted) candidates.push_back(file_->path.parent_path() / name);
  for (const std::filesystem::path& dir : options_.include_dirs) candidates.push_back(dir / name);
  std::string reader_failure;  // why the caller's reader threw, for the error below
  for (const std::filesystem::path& candidate : candidates) {
    std::optional<std::string> text;
    try {  // the reader is the caller's code; a throwing one must not unwind through us
      if (reader_) text = reader_(candidate);
    } catch (const std::exception& e) {
      if (reader_failure.empty()) reader_failure = fmt::format(" ({}: {})", candidate.string(), e.what());
    } catch (...) {
      if (reader_failure.empty()) reader_failure = fmt::format(" ({}: the reader failed)", candidate.string());
    }
    if (!text) continue;
    if (pragma_once_.count(candidate.lexically_normal().string()) != 0) return;
    if (!ChargeWork(text->size() + 64, column)) return;
    FileState included{candidate, candidate.string(), 0, {}};
    FileState* includer = file_;
    const LogicalLine* include_line = line_;
    ProcessFile(*text, &included, depth + 1);
    file_ = includer;
    line_ = include_line;
    return;
  }
  Error(column, DiagnosticCode::kIncludeNotFound, fmt::format("cannot open include file '{}'{}", name, reader_failure));
}

void Preprocessor::HandleLine(const std::vector<Token>& rest, int column) {
  std::vector<Token> tokens = Expand(rest, 0);
  std::size_t i = NextNonSpace(tokens, 0);
  std::string number = i < tokens.size() ? tokens[i].text : "";
  bool valid = !number.empty() && number.size() <= 9 && std::all_of(number.begin(), number.end(), IsDigit);
  if (!valid || std::stoi(number) == 0) {
    Error(ColumnAt(tokens, i, column), DiagnosticCode::kMalformedDirective,
          "#line needs a line number from 1 to 999999999");
    return;
  }
  std::size_t j = NextNonSpace(tokens, i + 1);
  if (j < tokens.size()) {
    const std::string& text = tokens[j].text;
    if (tokens[j].kind != TokenKind::kString || text.size() < 2 || text.back() != '"') {
      Error(tokens[j].column, DiagnosticCode::kMalformedDirective, "#line expects a file name in double quotes");
      return;
    }
    file_->name = text.substr(1, text.size() - 2);
  }
  file_->line_offset = std::stoi(number) - (line_->end_line + 1);
}

// Prosser's algorithm: replacements are pushed back onto the input, so a function-like macro
// name produced by one expansion can take its arguments from the text that follows, and hide
// sets stop recursion. `pending` holds the rest of the input reversed (next token at the back).
std::vector<Token> Preprocessor::Expand(std::vector<Token> input, int depth) {
  if (depth > kMaxExpansionDepth) {
    Error(ColumnAt(input, 0, 0), DiagnosticCode::kExpansionLimit, "macro arguments nested too deeply");
    return input;
  }
  std::vector<Token> output;
  std::vector<Token> pending(std::make_move_iterator(input.rbegin()), std::make_move_iterator(input.rend()));
  while (!pending.empty() && !stopped_) {
    Token token = std::move(pending.back());
    pending.pop_back();
    auto macro = token.kind == TokenKind::kIdentifier ? macros_.find(token.text) : macros_.end();
    std::vector<Token> replacement;
    if (macro == macros_.end() || InHideSet(token.hide_set, macro->second.id) ||
        !ReplaceMacro(macro->second, token, &pending, depth, &replacement)) {
      output.push_back(std::move(token));
      continue;
    }
    // Each piece's hide set was built in time proportional to its size, so that is work too.
    std::size_t units = kTokenWork;
    for (const Token& piece : replacement) {
      units += piece.text.size() + kTokenWork + (piece.hide_set ? piece.hide_set->size() : 0);
    }
    if (!ChargeWork(units, token.column)) break;
    pending.insert(pending.end(), std::make_move_iterator(replacement.rbegin()),
                   std::make_move_iterator(replacement.rend()));
  }
  return output;
}

// Builds the replacement for one use of `macro`, taking a function-like macro's arguments off
// `pending`. False when `name` is not a use (no argument list follows) or the call is bad.
bool Preprocessor::ReplaceMacro(const Macro& macro, const Token& name, std::vector<Token>* pending, int depth,
                                std::vector<Token>* out) {
  HideSet hide_set = name.hide_set;
  Args args;
  if (macro.function_like) {
    std::size_t rparen = 0;
    if (!CollectArguments(macro, name, *pending, &args, &rparen)) return false;
    hide_set = HideSetIntersection(hide_set, (*pending)[rparen].hide_set);
    pending->resize(rparen);
  }
  hide_set = HideSetUnion(hide_set, macro.self);
  if (hide_set->size() > kMaxMacroNesting) {
    Error(name.column, DiagnosticCode::kExpansionLimit,
          fmt::format("macros nested more than {} deep: each expands into the next (at '{}'; a chain of "
                      "#defines each naming the next?)",
                      kMaxMacroNesting, name.text));
    stopped_ = true;
    return false;
  }
  *out = Substitute(macro, args, depth);
  for (Token& token : *out) {
    token.hide_set = HideSetUnion(token.hide_set, hide_set);
    token.column = name.column;
    token.offset = -1;
  }
  return true;
}

bool Preprocessor::CollectArguments(const Macro& macro, const Token& name, const std::vector<Token>& pending,
                                    Args* args, std::size_t* rparen) {
  std::size_t i = pending.size();
  while (i > 0 && pending[i - 1].kind == TokenKind::kSpace) --i;
  if (i == 0 || !IsPunct(pending[i - 1], "(")) return false;
  const std::size_t start = --i;
  // Find the closing parenthesis before copying anything: on a line with many unterminated
  // calls, each one scans to the end. The scan is charged as work, which bounds that.
  for (int nesting = 0; i > 0 && (nesting > 0 || !IsPunct(pending[i - 1], ")")); --i) {
    nesting += IsPunct(pending[i - 1], "(") ? 1 : IsPunct(pending[i - 1], ")") ? -1 : 0;
  }
  if (!ChargeWork(start - i + 1, name.column)) return false;
  if (i == 0) {
    Error(name.column, DiagnosticCode::kMacroInvocation,
          fmt::format("unterminated argument list invoking macro '{}'", name.text));
    return false;
  }
  *rparen = i - 1;
  args->emplace_back();
  int nesting = 0;
  for (std::size_t k = start; k-- > i;) {
    const Token& token = pending[k];
    nesting += IsPunct(token, "(") ? 1 : IsPunct(token, ")") ? -1 : 0;
    if (nesting == 0 && IsPunct(token, ",")) {
      args->emplace_back();
    } else {
      args->back().push_back(token);
    }
  }
  return CheckArgumentCount(macro, name, args);
}

bool Preprocessor::CheckArgumentCount(const Macro& macro, const Token& name, Args* args) {
  for (std::vector<Token>& arg : *args) TrimSpaces(&arg);
  std::size_t expected = macro.params.size();
  if (expected == 0 && args->size() == 1 && args->front().empty()) args->clear();
  if (args->size() == expected) return true;
  Error(name.column, DiagnosticCode::kMacroInvocation,
        fmt::format("macro '{}' expects {} argument{}, got {}", name.text, expected,
                                 expected == 1 ? "" : "s", args->size()));
  return false;
}

std::vector<Token> Preprocessor::Substitute(const Macro& macro, const Args& args, int depth) {
  const std::vector<Token>& body = macro.body;
  auto param_index = [&](std::size_t i) -> int {
    if (i >= body.size() || body[i].kind != TokenKind::kIdentifier) return -1;
    auto it = std::find(macro.params.begin(), macro.params.end(), body[i].text);
    return it == macro.params.end() ? -1 : static_cast<int>(it - macro.params.begin());
  };
  std::vector<std::optional<std::vector<Token>>> expanded(args.size());
  std::vector<Token> out;
  for (std::size_t i = 0; i < body.size(); ++i) {
    std::size_t next = NextNonSpace(body, i + 1);
    int param = param_index(i);
    if (IsPunct(body[i], "##") && next < body.size()) {
      while (!out.empty() && out.back().kind == TokenKind::kSpace) out.pop_back();
      Paste(&out, param_index(next) >= 0 ? args[param_index(next)] : std::vector<Token>{body[next]});
      i = next;
    } else if (param >= 0 && next < body.size() && IsPunct(body[next], "##")) {
      out.insert(out.end(), args[param].begin(), args[param].end());  // ## pastes arguments as written
    } else if (param >= 0) {
      // Other arguments are fully expanded before substitution, as in C.
      if (!expanded[param]) expanded[param] = Expand(args[param], depth + 1);
      out.insert(out.end(), expanded[param]->begin(), expanded[param]->end());
    } else {
      out.push_back(body[i]);
    }
  }
  return out;
}

}  // namespace

std::optional<std::string> ReadFileFromDisk(const std::filesystem::path& path) {
  // Only regular files: a FIFO named by an #include would block until someone writes to it.
  if (!InputFileProblem(path, /*pipes_allowed=*/false).ok()) return std::nullopt;
  Result<std::string> text = ReadInputFile(path, kMaxProgramFileBytes);
  if (!text) return std::nullopt;
  return std::move(*text);
}

PreprocessResult Preprocess(std::string_view text, const std::string& file_name, const PreprocessOptions& options,
                            const FileReader& reader) {
  // Only std::bad_alloc can get here (every input problem is a diagnostic); it must not escape.
  try {
    Preprocessor preprocessor(options, reader);
    return preprocessor.Run(text, file_name);
  } catch (const std::exception& e) {
    PreprocessResult result;
    result.diagnostics.Error({file_name, 0, 0}, DiagnosticCode::kPreprocessorFailure,
                             fmt::format("preprocessing failed: {}", e.what()));
    return result;
  }
}

}  // namespace vs11
