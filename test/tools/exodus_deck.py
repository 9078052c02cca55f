#!/usr/bin/python3
"""exodus_deck.py DECK.xml OUT.xml MESH.e: the input deck with every body's
mesh read from the Exodus II file MESH.e (Generator = Exodus, Element Block
= the body's name) instead of its generator; everything else unchanged.
With a Gmsh file MESH.msh (test/tools/write_gmsh_mesh.py) the body is read
from it instead (Generator = Gmsh, its Physical Volume, or Physical Surface
for a 2-D element type, = the body's name).
Exit status 0, or 2 on bad usage or a deck without bodies."""
import sys
import xml.etree.ElementTree as ET


def main():
    if len(sys.argv) != 4:
        print("usage: exodus_deck.py DECK.xml OUT.xml MESH.e", file=sys.stderr)
        sys.exit(2)
    deck, out, mesh = sys.argv[1:]
    tree = ET.parse(deck)
    root = tree.getroot()
    bodies = None
    for m in root.findall("ParameterList"):
        if m.get("name") == "Mesh":
            for b in m.findall("ParameterList"):
                if b.get("name") == "Bodies":
                    bodies = b
    if bodies is None or not len(bodies.findall("ParameterList")):
        print(f"exodus_deck.py: {deck} has no Mesh/Bodies", file=sys.stderr)
        sys.exit(2)
    for body in bodies.findall("ParameterList"):
        gen = None
        for p in body.findall("Parameter"):
            if p.get("name") == "Generator":
                gen = p
        if gen is None:
            gen = ET.SubElement(body, "Parameter", name="Generator", type="string")
        old = gen.get("value") or "Rectangle"
        gmsh = mesh.endswith(".msh")
        gen.set("value", "Gmsh" if gmsh else "Exodus")
        for sub in body.findall("ParameterList"):
            if sub.get("name") == old:
                body.remove(sub)
        ex = ET.SubElement(body, "ParameterList", name="Gmsh" if gmsh else "Exodus")
        ET.SubElement(ex, "Parameter", name="File", type="string", value=mesh)
        if gmsh:
            types = [p.get("value") for e in body.findall("ParameterList") if e.get("name") == "Element"
                     for p in e.findall("Parameter") if p.get("name") == "Type"]
            group = "Physical Surface" if types and types[0].startswith("Quad") else "Physical Volume"
            ET.SubElement(ex, "Parameter", name=group, type="string", value=body.get("name"))
        else:
            ET.SubElement(ex, "Parameter", name="Element Block", type="string", value=body.get("name"))
    tree.write(out)


if __name__ == "__main__":
    main()
