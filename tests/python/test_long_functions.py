"""scripts/long_functions.py finds the functions over a length: counted from a tree written here,
whose functions' lengths are known by construction."""
import importlib.util
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[2]
spec = importlib.util.spec_from_file_location("long_functions", ROOT / "scripts" / "long_functions.py")
long_functions = importlib.util.module_from_spec(spec)
spec.loader.exec_module(long_functions)


def c_function(name, lines, head="static int"):
    """A C function of exactly `lines` lines (signature to closing brace), with braces, strings
    and comments inside that must not end it early."""
    body = [f'    const char *s{i} = "}}{{ // not a comment"; /* }} */' for i in range(lines - 3)]
    return "\n".join([f"{head} {name}(int a,", "        int b) {", *body, "}"]) + "\n"


def test_c_cpp_and_python_functions_over_the_length(tmp_path):
    (tmp_path / "csrc" / "x").mkdir(parents=True)
    (tmp_path / "csrc" / "bench").mkdir()
    (tmp_path / "fmu").mkdir()
    (tmp_path / "python" / "pkg").mkdir(parents=True)
    (tmp_path / "csrc" / "x" / "a.cpp").write_text(
        "namespace n {\nstruct S {\n" + c_function("member", 81, "    int") + "};\n"
        + c_function("short_one", 80) + "}  // namespace n\n"
        + 'extern "C" {\n' + c_function("stewart_long", 95, "int") + "}\n")
    (tmp_path / "csrc" / "bench" / "b.cpp").write_text(c_function("benchmark", 200))
    (tmp_path / "fmu" / "m.c").write_text(
        "#define STEP(x) \\\n  do { x; } while (0)\n" + c_function("main", 90, "int"))
    (tmp_path / "python" / "pkg" / "p.py").write_text(
        "def long_one():\n" + "    x = 1\n" * 85 + "\n\ndef short():\n    return 1\n")
    rows = long_functions.long_functions(tmp_path, 80)
    assert [(n, where.split(":")[0], name) for n, where, name in rows] == [
        (95, "csrc/x/a.cpp", "stewart_long"), (90, "fmu/m.c", "main"),
        (86, "python/pkg/p.py", "long_one"), (81, "csrc/x/a.cpp", "member")]


def test_exit_status_says_whether_any_function_is_over(tmp_path, capsys):
    """The gate's status (ctest long_function_gate): 1 with a function over the length, and 0
    once it is split, with the count printed either way."""
    (tmp_path / "csrc").mkdir()
    source = tmp_path / "csrc" / "a.c"
    source.write_text(c_function("long_one", 81))
    assert long_functions.main([str(tmp_path)]) == 1
    assert capsys.readouterr().out.endswith("1 functions over 80 lines\n")
    source.write_text(c_function("first_half", 41) + c_function("second_half", 41))
    assert long_functions.main([str(tmp_path)]) == 0
    assert capsys.readouterr().out == "0 functions over 80 lines\n"
    assert long_functions.main(["--over", "40", str(tmp_path)]) == 1
