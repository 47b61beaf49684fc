#!/usr/bin/env python3
"""Makes the fuzzer's seed corpus from the project's MJCF models.

    python3 tests/fuzz/make_seed_corpus.py OUT_DIR [--max-bytes N]

Every model under models/ and tests/ that loads from a string on its own becomes one
file in OUT_DIR (emptied first). A model's <include file="..."/> elements are replaced by
the included file's contents (recursively), as the loader would; a model that still
names a file after that (<model file>, a mesh, height field, texture or skin file, or a
meshdir/texturedir/assetdir) is skipped, because the fuzzer loads text with no files
around it. Models larger than --max-bytes (the fuzzer's -max_len) are skipped, since
libFuzzer would cut them short. Equal texts are kept once.
"""
import argparse
import hashlib
import pathlib
import re
import shutil
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]

# The models the corpus is made of, relative to the repository; not the fuzzer's own
# findings (tests/fuzz/findings), which would stop every run at its first input.
GLOBS = ["models/*.xml", "tests/**/*.xml"]
EXCLUDE = "tests/fuzz"

INCLUDE = re.compile(r'<include\s+file\s*=\s*"([^"]*)"\s*/>')
# Anything that still points at a file once includes are inlined.
NAMES_A_FILE = re.compile(
    r'\b(file|fileback|filedown|filefront|fileleft|fileright|fileup|meshdir|texturedir|assetdir)'
    r'\s*=')
XML_DECLARATION = re.compile(r"^\s*<\?xml[^>]*\?>")
MUJOCO_OPEN = re.compile(r"<mujoco\b[^>]*?(/?)>")
COMMENT = re.compile(r"<!--.*?-->", re.S)


def included_body(path: pathlib.Path, depth: int) -> str:
    """The children of an included file's <mujoco> root, with its own includes inlined."""
    text = inline_includes(read(path), path.parent, depth + 1)
    text = XML_DECLARATION.sub("", text)
    opening = MUJOCO_OPEN.search(COMMENT.sub(lambda m: " " * len(m.group(0)), text))
    if not opening:
        raise ValueError(f"{path}: no <mujoco> root")
    if opening.group(1) == "/":
        return ""
    close = text.rfind("</mujoco>")
    if close < opening.end():
        raise ValueError(f"{path}: no </mujoco>")
    return text[opening.end():close]


def read(path: pathlib.Path) -> str:
    """A file's text; bytes that are not UTF-8 survive the round trip unchanged."""
    return path.read_bytes().decode("utf-8", errors="surrogateescape")


def inline_includes(text: str, folder: pathlib.Path, depth: int = 0) -> str:
    if depth > 10:
        raise ValueError("includes nested too deep")
    return INCLUDE.sub(lambda m: included_body(folder / m.group(1), depth), text)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=pathlib.Path)
    parser.add_argument("--max-bytes", type=int, default=16384)
    args = parser.parse_args()

    if args.out.exists():
        shutil.rmtree(args.out)
    args.out.mkdir(parents=True)

    paths = sorted({p for g in GLOBS for p in ROOT.glob(g)
                    if p.is_file() and not p.relative_to(ROOT).as_posix().startswith(EXCLUDE + "/")})
    seen = set()
    kept = inlined = needs_files = too_big = duplicates = 0
    for path in paths:
        rel = path.relative_to(ROOT)
        raw = read(path)
        try:
            text = inline_includes(raw, path.parent)
        except (OSError, ValueError) as e:
            print(f"skip {rel}: include not inlined ({e})", file=sys.stderr)
            needs_files += 1
            continue
        if NAMES_A_FILE.search(COMMENT.sub("", text)):
            needs_files += 1
            continue
        data = text.encode("utf-8", errors="surrogateescape")
        if len(data) > args.max_bytes:
            too_big += 1
            continue
        digest = hashlib.sha1(data).hexdigest()
        if digest in seen:
            duplicates += 1
            continue
        seen.add(digest)
        inlined += text != raw
        name = str(rel.with_suffix("")).replace("/", "__")
        (args.out / f"{name}.xml").write_bytes(data)
        kept += 1

    print(f"seed corpus {args.out}: {kept} models ({inlined} with includes inlined); "
          f"skipped {needs_files} that name files, {too_big} over {args.max_bytes} bytes, "
          f"{duplicates} duplicates")
    return 0 if kept else 1


if __name__ == "__main__":
    sys.exit(main())
