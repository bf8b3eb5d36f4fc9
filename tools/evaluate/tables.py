"""Tables as CSV files and Markdown: rows are dicts, columns in the order given; numbers are
written with a fixed number of decimals, None as an empty cell (CSV) or "-" (Markdown)."""

import csv


def cell(v, decimals=2):
    if v is None:
        return ""
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        return f"{v:.{decimals}f}"
    return str(v)


def write_csv(path, rows, columns):
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(columns)
        for r in rows:
            w.writerow([cell(r.get(c), 3) for c in columns])
    return path


def markdown(rows, columns, headers=None, decimals=2):
    headers = headers or columns
    out = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(columns)]
    for r in rows:
        out.append("| " + " | ".join((cell(r.get(c), decimals) or "-").replace("|", "/")
                                     for c in columns) + " |")
    return "\n".join(out)
