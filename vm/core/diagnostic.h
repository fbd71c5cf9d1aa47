// Problems found in user input (source text, bytecode, files), collected rather than thrown so that
// one pass can report many of them. Programmer errors use assert instead.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "vm/core/name_table.h"

namespace vs11 {

struct SourceLoc {
  std::string file;  // as the user named it; empty for bytecode without a source map
  int line = 0;      // 1-based; 0 = unknown
  int column = 0;    // 1-based; 0 = unknown
  friend bool operator==(const SourceLoc&, const SourceLoc&) = default;
};

enum class Severity { kError, kWarning, kNote };
inline constexpr NameTable kSeverityNames("severity", {
    Choice(Severity::kError, "error"), Choice(Severity::kWarning, "warning"), Choice(Severity::kNote, "note")});

// What kind of problem a diagnostic reports, one code per kind, so that tests and tools can tell
// problems apart without matching message wording. The printed name (second column) is stable: it
// is part of the output format ("FILE:LINE:COL: error: MESSAGE [name]") and of `--json`; add new
// codes, never rename or reuse one.
#define VS11_DIAGNOSTIC_CODES(X)                                                                  \
  /* The default of a Diagnostic made field by field; every report names a code of its own. */    \
  X(kUnclassified, "unclassified")                                                                \
  X(kCannotReadFile, "cannot-read-file")                                                          \
  X(kCannotWriteFile, "cannot-write-file")                                                        \
  /* Jobs and their files (irradiance/jobs/, irradiance/io/). */                                  \
  X(kOutputInUse, "output-in-use")                                                                \
  X(kNoSuchInput, "no-such-input")                                                                \
  X(kImageIoModule, "image-io-module")                                                            \
  X(kFaceSize, "face-size")                                                                       \
  X(kGnuplot, "gnuplot")                                                                          \
  /* A program compiled into the binary that does not assemble: a build problem, not a user's. */ \
  X(kEmbeddedProgram, "embedded-program")                                                         \
  /* Lexer (vm/asm/lexer.h). */                                                                   \
  X(kUnexpectedCharacter, "unexpected-character")                                                 \
  X(kMalformedNumber, "malformed-number")                                                         \
  /* Preprocessor (vm/asm/preprocessor.h). */                                                     \
  X(kUnknownDirective, "unknown-directive")                                                       \
  X(kMalformedDirective, "malformed-directive")                                                   \
  X(kUnbalancedConditional, "unbalanced-conditional")                                             \
  X(kConditionExpression, "condition-expression")                                                 \
  X(kUnterminatedComment, "unterminated-comment")                                                 \
  X(kMacroDefinition, "macro-definition")                                                         \
  X(kMacroInvocation, "macro-invocation")                                                         \
  X(kIncludeNotFound, "include-not-found")                                                        \
  X(kIncludeTooDeep, "include-too-deep")                                                          \
  X(kExpansionLimit, "expansion-limit")                                                           \
  X(kTooManyMacros, "too-many-macros")                                                            \
  X(kErrorDirective, "error-directive")                                                           \
  X(kWarningDirective, "warning-directive")                                                       \
  X(kPreprocessorFailure, "preprocessor-failure")                                                 \
  /* Assembler syntax (vm/asm/assembler.h). */                                                    \
  X(kVersionStatement, "version-statement")                                                       \
  X(kUnknownInstruction, "unknown-instruction")                                                   \
  X(kNotInVs11, "not-in-vs_1_1")                                                                  \
  X(kOperandCount, "operand-count")                                                               \
  X(kUnexpectedToken, "unexpected-token")                                                         \
  X(kDeclarationUsage, "dcl-usage")                                                               \
  X(kDestinationSyntax, "destination-syntax")                                                     \
  X(kSourceModifier, "source-modifier")                                                           \
  X(kExpectedRegister, "expected-register")                                                       \
  X(kUnknownRegister, "unknown-register")                                                         \
  X(kRegisterNumberTooLarge, "register-number-too-large")                                         \
  X(kConstantIndexSyntax, "constant-index-syntax")                                                \
  X(kWriteMaskSyntax, "write-mask-syntax")                                                        \
  X(kSwizzleSyntax, "swizzle-syntax")                                                             \
  X(kExpectedNumber, "expected-number")                                                           \
  X(kNumberOutOfRange, "number-out-of-range")                                                     \
  X(kNumberUnderflow, "number-underflow")                                                         \
  X(kNotInModel, "not-in-model")                                                                  \
  X(kPredicateSyntax, "predicate-syntax")                                                         \
  /* Validator (vm/asm/validator.h, spec §6). */                                                 \
  X(kVersionToken, "version-token")                                                               \
  X(kMisplacedDeclaration, "misplaced-declaration")                                               \
  X(kTooManySlots, "too-many-slots")                                                              \
  X(kNoSuchRegister, "no-such-register")                                                          \
  X(kReadOnlyDestination, "read-only-destination")                                                \
  X(kWriteOnlySource, "write-only-source")                                                        \
  X(kRelativeAddressing, "relative-addressing")                                                   \
  X(kAddressNotWritten, "address-not-written")                                                    \
  X(kAddressWrite, "address-write")                                                               \
  X(kWriteMask, "write-mask")                                                                     \
  X(kScalarOutputMask, "scalar-output-mask")                                                      \
  X(kReadPorts, "read-ports")                                                                     \
  X(kMatrixOperand, "matrix-operand")                                                             \
  X(kScalarSwizzle, "scalar-swizzle")                                                             \
  X(kUninitializedRegister, "uninitialized-register")                                             \
  X(kUninitializedLanes, "uninitialized-lanes")                                                   \
  X(kUndeclaredInput, "undeclared-input")                                                         \
  X(kPositionNotWritten, "position-not-written")                                                  \
  X(kPositionPartlyWritten, "position-partly-written")                                            \
  X(kBadDeclaration, "bad-declaration")                                                           \
  X(kDuplicateDeclaration, "duplicate-declaration")                                               \
  X(kBadDefinition, "bad-definition")                                                             \
  X(kDuplicateDefinition, "duplicate-definition")                                                 \
  X(kTooManyDefinitions, "too-many-definitions")                                                  \
  X(kUnmatchedFlowControl, "unmatched-flow-control")                                              \
  X(kNestingTooDeep, "nesting-too-deep")                                                          \
  X(kUndefinedLabel, "undefined-label")                                                           \
  X(kDuplicateLabel, "duplicate-label")                                                           \
  X(kLoopRegisterOutsideLoop, "loop-register-outside-loop")                                       \
  X(kBadOperand, "bad-operand")                                                                   \
  /* Bytecode decoder (vm/asm/bytecode.h, spec §4). */                                           \
  X(kBytecodeTruncated, "bytecode-truncated")                                                     \
  X(kBytecodeTrailingWords, "bytecode-trailing-words")                                            \
  X(kBytecodeMalformedToken, "bytecode-malformed-token")                                          \
  X(kBytecodeUnknownOpcode, "bytecode-unknown-opcode")                                            \
  X(kBytecodeRegisterType, "bytecode-register-type")                                              \
  X(kBytecodeDeclarationUsage, "bytecode-dcl-usage")                                              \
  /* Constant files and --const (vm/io/vertex_io.h). */                                           \
  X(kConstantLine, "constant-line")                                                               \
  X(kConstantValue, "constant-value")                                                             \
  X(kConstantRegisterRange, "constant-register-range")                                            \
  /* Vertex CSV files (vm/io/vertex_io.h). */                                                     \
  X(kCsvSeparator, "csv-separator")                                                               \
  X(kCsvNumber, "csv-number")                                                                     \
  X(kCsvTooManyValues, "csv-too-many-values")                                                     \
  X(kCsvMissingCell, "csv-missing-cell")                                                          \
  X(kCsvColumns, "csv-columns")                                                                   \
  /* A run's --input flag and the registers nobody sets (vm/io/vertex_io.h). */                   \
  X(kInputFlag, "input-flag")                                                                     \
  X(kUnsetRegister, "unset-register")                                                             \
  /* Meshes and vertex buffers (vm/mesh/). */                                                     \
  X(kMeshWire, "mesh-wire")                                                                       \
  X(kBufferElement, "buffer-element")                                                             \
  X(kBufferLayout, "buffer-layout")                                                               \
  X(kBufferSize, "buffer-size")                                                                   \
  X(kBinding, "binding")                                                                          \
  X(kMeshAttributeMissing, "mesh-attribute-missing")                                              \
  X(kBonePalette, "bone-palette")                                                                 \
  /* Vertex textures (vm/core/vertex_texture.h) and --texture. */                                 \
  X(kTexture, "texture")                                                                          \
  /* Metadata lines of verified programs (vm/reference/program_metadata.h). */                   \
  X(kMetadataSyntax, "metadata-syntax")                                                           \
  X(kMetadataDuplicateKey, "metadata-duplicate-key")                                              \
  X(kMetadataUnknownKey, "metadata-unknown-key")                                                  \
  X(kMetadataValue, "metadata-value")                                                             \
  /* Engines (vm/engines/engine_factory.h) and OpenGL ES (vm/gl/). */                             \
  X(kEngineUnavailable, "engine-unavailable")                                                     \
  X(kGlUnavailable, "gl-unavailable")                                                             \
  X(kGlCompile, "gl-compile")                                                                     \
  X(kGlError, "gl-error")                                                                         \
  /* Options of a job or a tool whose values are wrong: a usage error (irradiance/jobs/). */      \
  X(kOptionValue, "option-value")                                                                 \
  /* An output that is one of the run's inputs (vm/core/input_file.h). */                         \
  X(kOutputOverwritesInput, "output-overwrites-input")                                            \
  /* An output that exists and is not to be replaced or continued (irradiance/jobs/). */          \
  X(kOutputExists, "output-exists")                                                               \
  /* A file that should hold records of irrmap batch and does not (irradiance/jobs/). */          \
  X(kBatchRecord, "batch-record")                                                                 \
  /* Two inputs whose --per-file outputs would have one name (irradiance/jobs/). */               \
  X(kPerFileCollision, "per-file-collision")                                                      \
  /* A result beyond float range (irradiance/jobs/float_range.h). */                              \
  X(kBeyondFloatRange, "beyond-float-range")                                                      \
  X(kOutOfMemory, "out-of-memory")                                                                \
  /* SPIR-V that spirv-val refuses (vm/translate/glslang_compiler.h). */                          \
  X(kInvalidSpirv, "invalid-spirv")                                                               \
  /* The mesh loader's child process died in vs11's own checks or conversion, not in Assimp: a */  \
  /* bug in vs11, which the fuzz target fails on (vm/mesh/mesh_sandbox.h). */                     \
  X(kMeshConverterCrashed, "mesh-converter-crashed")

enum class DiagnosticCode {
#define VS11_DIAGNOSTIC_ENUMERATOR(code, name) code,
  VS11_DIAGNOSTIC_CODES(VS11_DIAGNOSTIC_ENUMERATOR)
#undef VS11_DIAGNOSTIC_ENUMERATOR
};

// The stable printed name of `code`, e.g. "uninitialized-lanes".
std::string_view DiagnosticCodeName(DiagnosticCode code);

struct Diagnostic {
  SourceLoc loc;
  Severity severity = Severity::kError;
  DiagnosticCode code = DiagnosticCode::kUnclassified;
  std::string message;
  // For bytecode problems: the index of the 32-bit word at fault, or -1.
  long word_offset = -1;
};

// "FILE:LINE:COL: error: MESSAGE [code]" (parts that are unknown are left out, and so is the code
// when it is kUnclassified).
std::string FormatDiagnostic(const Diagnostic& diagnostic);

class Diagnostics {
 public:
  // After this many errors, further errors are counted but not kept (a runaway file stays bounded).
  static constexpr int kMaxKeptErrors = 50;

  void Error(SourceLoc loc, DiagnosticCode code, std::string message);
  void Warning(SourceLoc loc, DiagnosticCode code, std::string message);
  void Add(Diagnostic diagnostic);
  void Append(const Diagnostics& other);

  bool HasErrors() const { return error_count_ > 0; }
  int error_count() const { return error_count_; }
  const std::vector<Diagnostic>& all() const { return items_; }
  // Every kept diagnostic, one formatted line each, plus a line for errors that were not kept.
  std::string ToString() const;

 private:
  std::vector<Diagnostic> items_;
  int error_count_ = 0;
};

}  // namespace vs11
