"""vs11.assemble / vs11.load / Program: tokens, disassembly, validation, counts, errors."""
import numpy as np
import pytest

import vs11

PASS_THROUGH = "vs_1_1\ndcl_position v0\ndcl_normal v3\nmov oPos, v0\nmov oD0, v3\n"


def test_assemble_gives_tokens_that_start_with_the_version_and_end_with_end():
    program = vs11.assemble(PASS_THROUGH)
    assert program.tokens.dtype == np.uint32
    assert program.tokens[0] == 0xFFFE0101
    assert program.tokens[-1] == 0x0000FFFF
    assert program.inputs == ["v0", "v3"]
    assert program.outputs == ["oPos", "oD0"]


def test_disassembly_reassembles_to_the_same_tokens(programs_dir):
    program = vs11.load(programs_dir / "skinning.vsh")
    again = vs11.assemble(program.disassemble(), name="again.vsh")
    np.testing.assert_array_equal(again.tokens, program.tokens)


def test_bytecode_file_loads_to_the_same_tokens(tmp_path, programs_dir):
    program = vs11.load(programs_dir / "directional_light.vsh")
    path = tmp_path / "light.vso"
    program.tokens.astype("<u4").tofile(path)
    np.testing.assert_array_equal(vs11.load(path).tokens, program.tokens)


def test_count_matches_the_paper_program_slots(programs_dir):
    counts = vs11.load(programs_dir / "sh9_irradiance.vsh").count()
    assert counts["slots"] == 11
    assert counts["instructions"] == 11
    assert counts["constants"] == 7
    assert counts["inputs"] == 1


def test_fragment_metadata_is_honoured_and_can_be_overridden(programs_dir):
    text = (programs_dir / "sh9_irradiance.vsh").read_text()
    assert vs11.assemble(text, name="sh9.vsh").fragment
    with pytest.raises(vs11.AssemblyError, match="oPos"):
        vs11.assemble(text, name="sh9.vsh", fragment=False)


def test_assembly_error_carries_file_line_and_column():
    source = "vs_1_1\ndcl_position v0\nmov oPos, v0\nadd r0, v0, bogus7\n"
    with pytest.raises(vs11.AssemblyError) as caught:
        vs11.assemble(source, name="bad.vsh")
    error = caught.value
    assert isinstance(error, ValueError)
    assert str(error).startswith("bad.vsh:4:")
    first = error.diagnostics[0]
    assert (first["file"], first["line"], first["severity"]) == ("bad.vsh", 4, "error")
    assert first["column"] > 1
    assert first["text"].startswith("bad.vsh:4:%d: error: " % first["column"])


def test_validation_error_is_an_assembly_error():
    with pytest.raises(vs11.AssemblyError, match=r"<string>:2:\d+: error: .*r12"):
        vs11.assemble("vs_1_1\nmov r12, c0\nmov oPos, r12\n")


def test_missing_file_is_an_assembly_error(tmp_path):
    with pytest.raises(vs11.AssemblyError, match="missing.vsh"):
        vs11.load(tmp_path / "missing.vsh")


def test_max_constants_widens_the_constant_file():
    source = "vs_1_1\ndcl_position v0\nadd oPos, v0, c200\n"
    with pytest.raises(vs11.AssemblyError, match="c200"):
        vs11.assemble(source)
    assert vs11.assemble(source, max_constants=256).count()["constants"] == 1
    with pytest.raises(ValueError, match="max_constants"):
        vs11.assemble(source, max_constants=10)


def test_validate_returns_warnings_of_a_valid_program():
    program = vs11.assemble(PASS_THROUGH)
    assert program.validate() == []
