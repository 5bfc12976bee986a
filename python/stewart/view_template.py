"""The page of stewart.view without its title and data: view_page.html with view_page.js and
three.js inlined. One assembly for both writers of the page: stewart.view fills it in at run time,
and the C++ command lines (stewart-solve --view) embed it at build time, from this file run as a
script (standard library only: it runs before the package is installed):

    python view_template.py --three DIR --cpp OUT.cpp

writes OUT.cpp defining the template's parts for csrc/cli/view_page.cpp; without three.js in DIR
the parts are empty and the reason (naming scripts/setup.sh) is what --view says."""
from __future__ import annotations

import argparse
import json
import os
import pathlib
import re

_HERE = pathlib.Path(__file__).resolve().parent
#: The longest URL Chromium loads (2 MiB): each module's data: URL must fit (three.core.js of
#: three 0.187.0 makes 1.5 MB).
CHROMIUM_MAX_URL = 2 * 1024 * 1024
#: The places a page's own text goes: its title (HTML text) and its data (JSON, script_json).
TITLE, DATA = "@TITLE@", "/*DATA*/"


def three_dir(folder=None) -> pathlib.Path:
    """Where the package's copy of three.js is (installed with the package from the npm
    package scripts/setup.sh fetches); STEWART_THREE_DIR overrides it."""
    folder = pathlib.Path(folder or os.environ.get("STEWART_THREE_DIR", _HERE / "three"))
    for name in ("three.core.js", "three.module.js", "OrbitControls.js"):
        if _three_path(folder, name) is None:
            raise FileNotFoundError(
                f"three.js is not in {folder} ({name} missing): scripts/setup.sh fetches the "
                "pinned npm package `three` and the package install copies it here; run it and "
                "reinstall, or set STEWART_THREE_DIR to an unpacked npm package of three")
    return folder


def _three_path(folder: pathlib.Path, name: str):
    """name in the package's flat copy or in an unpacked npm package; None if in neither."""
    for path in (folder / name, folder / "build" / name,
                 folder / "examples" / "jsm" / "controls" / name):
        if path.is_file():
            return path
    return None


def _three_file(folder: pathlib.Path, name: str) -> str:
    path = _three_path(folder, name)
    if path is None:
        raise FileNotFoundError(f"{name} is not in {folder}")
    return path.read_text(encoding="utf-8")


def _data_url(code: str) -> str:
    """A JavaScript data: URL of code, percent-encoding only what a URL would change ('%', '#',
    and the line breaks and tabs a URL parser drops): a few percent larger than the code."""
    for ch, esc in (("%", "%25"), ("#", "%23"), ("\n", "%0A"), ("\r", "%0D"), ("\t", "%09")):
        code = code.replace(ch, esc)
    url = "data:text/javascript;charset=utf-8," + code
    if len(url.encode("utf-8")) > CHROMIUM_MAX_URL:
        raise ValueError(f"a three.js module makes a data: URL of {len(url)} characters, beyond "
                         f"the {CHROMIUM_MAX_URL} Chromium loads: use the pinned three.js")
    return url


def script_json(value) -> str:
    """JSON safe inside a <script> element: no '<' (so no '</script>' or '<!--')."""
    return json.dumps(value, separators=(",", ":")).replace("<", "\\u003c")


def html_text(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def template_parts(folder=None) -> list[str]:
    """The page as texts and the markers TITLE and DATA between them, each marker an element of
    its own: joining them with the title and the data in place of the markers gives the page."""
    folder = three_dir(folder)
    core = _three_file(folder, "three.core.js")
    module = _three_file(folder, "three.module.js").replace("'./three.core.js'", "'three/core'")
    imports = {"three/core": _data_url(core), "three": _data_url(module),
               "three/addons/controls/OrbitControls.js":
                   _data_url(_three_file(folder, "OrbitControls.js"))}
    page = (_HERE / "view_page.html").read_text(encoding="utf-8")
    app = (_HERE / "view_page.js").read_text(encoding="utf-8")
    if "</script" in app.lower() or "<!--" in app:  # would end or hide the inline script
        raise ValueError("view_page.js holds '</script' or '<!--': it cannot be inlined")
    version = (folder / "VERSION").read_text().strip() if (folder / "VERSION").is_file() else "?"
    # The template is split at its own markers first, so that no marker is looked for inside an
    # inserted text.
    parts = re.split("(" + re.escape(TITLE) + "|" + re.escape(DATA) + ")", page)
    for i, part in enumerate(parts):
        if part in (TITLE, DATA):
            continue
        part = part.replace("@THREE_VERSION@", version)
        for key, text in (("/*APP*/", app), ("/*IMPORTMAP*/", script_json({"imports": imports}))):
            part = part.replace(key, text, 1)
        parts[i] = part
    return parts


def fill(parts: list[str], title: str, data_json: str) -> str:
    """The page: parts with the title (plain text) and the data (script_json's text) in place."""
    return "".join(html_text(title) if p == TITLE else data_json if p == DATA else p
                   for p in parts)


def _cpp_literal(text: str) -> str:
    """text's UTF-8 bytes as C++ string literals of at most 4 KiB each (octal escapes: three
    digits at most, so no escape runs into the next character)."""
    out, line = [], []
    for byte in text.encode("utf-8"):
        c = chr(byte)
        line.append(c if 32 <= byte < 127 and c not in '"\\?' else f"\\{byte:03o}")
        if len(line) >= 4096:
            out.append('"' + "".join(line) + '"')
            line = []
    out.append('"' + "".join(line) + '"')
    return "\n".join(out)


def _write_cpp(path: pathlib.Path, three) -> None:
    """The template's parts as C++ (csrc/cli/view_page.cpp declares them; a marker part is the
    marker's text); with no three.js, no parts and the reason."""
    try:
        parts, missing = template_parts(three), ""
    except FileNotFoundError:
        parts, missing = [], (
            f"this build has no three.js (none in {three}): run scripts/setup.sh, which fetches "
            "the pinned npm package `three` into .cache/three, then build again (or configure "
            "with -DSTEWART_THREE_DIR=an unpacked npm package of three)")
    lines = ["// Generated by python/stewart/view_template.py: stewart.view's page template.",
             "#include <cstddef>", "namespace stewart {",
             f"extern const char kViewTemplateMissing[] = {_cpp_literal(missing)};",
             f"extern const std::size_t kViewTemplateParts = {len(parts)};"]
    texts = [f"{_cpp_literal(p)}" for p in parts]
    lines.append("extern const char *const kViewTemplate[] = {" +
                 (",\n".join(texts) if texts else "nullptr") + "};")
    lines.append("extern const std::size_t kViewTemplateSizes[] = {" +
                 (", ".join(str(len(p.encode("utf-8"))) for p in parts) or "0") + "};")
    lines.append("}  // namespace stewart")
    path.write_text("\n".join(lines) + "\n", encoding="ascii")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--three", required=True, help="the unpacked npm package three")
    parser.add_argument("--cpp", required=True, type=pathlib.Path, help="the C++ file to write")
    args = parser.parse_args()
    _write_cpp(args.cpp, args.three)
