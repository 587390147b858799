"""Reader of the selection CSV that `pounding records select -o` writes (tests only; pure Python).

Returns (meta, header, rows): the "# key: value" lines as a dict, the column names of the
period_s,target_g,mean_g,<id>... header, and the numeric rows as lists of floats.
"""


def read_selection_csv(path):
    meta, header, rows = {}, None, []
    for line in open(path):
        line = line.rstrip("\n")
        if line.startswith("# ") and ": " in line:
            k, v = line[2:].split(": ", 1)
            meta[k] = v
        elif line.startswith("period_s,"):
            header = line.split(",")
        elif line and header:
            rows.append([float(x) for x in line.split(",")])
    return meta, header, rows
