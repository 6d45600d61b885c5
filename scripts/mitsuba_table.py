"""The command line of a script that writes a table from Mitsuba 3 into a committed header
(scripts/named_media.py, scripts/plastic_reference.py): it writes the table, or with --check compares it with
the committed one (exit 1 and a diff where they differ, 77 where Mitsuba is not installed, as CTest's
SKIP_RETURN_CODE takes it)."""
import argparse
import difflib
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
SKIP = 77


def table_main(name, description, path, table):
    """`table(mi, variant)` gives the text of `path`; `name` prefixes every line printed."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--check", action="store_true", help="compare with the committed table, write nothing")
    parser.add_argument("--variant", default="llvm_ad_rgb")
    args = parser.parse_args()
    try:
        import mitsuba_scene

        mi = mitsuba_scene.open_mitsuba(args.variant)
        mi.set_log_level(mi.LogLevel.Error)  # not its warnings about spectra clamped into the sRGB gamut
    except ImportError as error:
        print(f"{name}: skipped, Mitsuba is not installed ({error})")
        return SKIP
    text = table(mi, args.variant)
    shown = path.relative_to(ROOT)
    if args.check:
        committed = path.read_text() if path.exists() else ""
        if committed != text:
            sys.stdout.writelines(difflib.unified_diff(committed.splitlines(True), text.splitlines(True), str(path),
                                                       "from Mitsuba"))
            print(f"{name}: the table differs from Mitsuba's; run scripts/{name}.py")
            return 1
        print(f"{name}: {shown} matches Mitsuba {mi.__version__}")
        return 0
    path.write_text(text)
    print(f"{name}: wrote {shown}")
    return 0
