"""Counts the memcheck errors (definite leaks included) with a frame in StewartPlatform.so,
StewartPlant.so or StewartPlantME.so, from
valgrind's XML report; exits 1 if there is any. usage: valgrind_verdict.py MEMCHECK.xml"""
import sys
import xml.etree.ElementTree as ET

OURS = ("StewartPlatform.so", "StewartPlant.so", "StewartPlantME.so")
root = ET.parse(sys.argv[1]).getroot()
total, ours = 0, []
for error in root.iter("error"):
    total += 1
    objs = [(f.findtext("obj") or "") + " " + (f.findtext("fn") or "") for f in error.iter("frame")]
    if any(n in o for o in objs for n in OURS):
        what = error.findtext("what") or (error.find("xwhat").findtext("text")
                                         if error.find("xwhat") is not None else "?")
        ours.append((error.findtext("kind"), what,
                     [o for o in objs if any(n in o for n in OURS)][:8]))
print(f"valgrind_fmu: {total} memcheck errors in the process (Python's own included), "
      f"{len(ours)} touching StewartPlatform.so, StewartPlant.so or StewartPlantME.so")
for kind, what, frames in ours:
    print(f"  {kind}: {what}")
    for f in frames:
        print(f"      {f}")
sys.exit(1 if ours else 0)
