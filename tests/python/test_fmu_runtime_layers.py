"""The FMU runtime's include graph: modules (a .h with its .c) form layers, no circle.

instance.h is the floor every module stands on (the instance's plain fields, included by all);
it includes no runtime module but the variable table. The edges into it are left out of the
graph, so instance.c (the life cycle, above the call table and logging) is checked like the rest.
"""
import re
from pathlib import Path

RUNTIME = Path(__file__).resolve().parents[2] / "fmu" / "runtime"
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.MULTILINE)


def module_graph():
    """Module name -> the runtime modules its .h and .c include (a model's files excluded)."""
    modules = {p.stem for p in RUNTIME.glob("*.[ch]")}
    graph = {m: set() for m in modules}
    for path in RUNTIME.glob("*.[ch]"):
        for name in INCLUDE.findall(path.read_text()):
            target = Path(name).stem
            if target in modules and target not in (path.stem, "instance"):
                graph[path.stem].add(target)
    return graph


def find_cycle(graph):
    """One include circle as a list of modules, or None."""
    state = {}

    def visit(node, stack):
        state[node] = "open"
        stack.append(node)
        for nxt in sorted(graph[node]):
            if state.get(nxt) == "open":
                return stack[stack.index(nxt):] + [nxt]
            if nxt not in state:
                found = visit(nxt, stack)
                if found:
                    return found
        stack.pop()
        state[node] = "done"
        return None

    for node in sorted(graph):
        if node not in state:
            found = visit(node, [])
            if found:
                return found
    return None


def test_instance_header_is_the_floor():
    names = {Path(n).stem for n in INCLUDE.findall((RUNTIME / "instance.h").read_text())}
    assert names <= {"config", "variables"}


def test_runtime_includes_have_no_circle():
    assert find_cycle(module_graph()) is None, " -> ".join(find_cycle(module_graph()))


def test_logging_is_a_leaf():
    # logging knows the instance's fields and nothing of the call order or the life cycle
    assert module_graph()["logging"] <= {"config", "variables"}


def test_the_cycle_finder_finds_a_circle():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": set()}) is None
