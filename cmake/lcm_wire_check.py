#!/usr/bin/env python3
"""Generates minenav/wire_check.hpp from the .lcm files: for every message type a check
of a payload's wire layout that runs BEFORE lcm-gen's decode().

Why: LCM 1.3.1's generated decoders trust the array counts in the payload. A count in
[2^29, 2^31) overflows `sizeof(T) * elements` (an int) inside __T_decode_array, the bounds
check passes and the decoder reads past the buffer (a 92-byte ladar_scan_t segfaults the
receiver); smaller absurd counts make it zero-fill gigabytes (`resize(count)`) before it
notices the payload is short. The check walks the payload exactly as decode() would and
refuses any count whose elements cannot fit in the bytes that remain, any negative count
and any string length outside the payload, without allocating anything. Its cost is
linear in the number of array elements of struct type (primitive arrays are checked in
O(1)).

Usage: lcm_wire_check.py OUT.hpp A.lcm B.lcm ...
"""
import os
import re
import sys

PRIMITIVE_SIZES = {
    "int8_t": 1, "boolean": 1, "byte": 1, "int16_t": 2, "int32_t": 4, "int64_t": 8,
    "float": 4, "double": 8,
}
INTEGER_TYPES = {"int8_t", "int16_t", "int32_t", "int64_t"}


def strip_comments(text):
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return re.sub(r"//[^\n]*", " ", text)


def parse(path):
    text = strip_comments(open(path, encoding="utf-8").read())
    package = re.search(r"\bpackage\s+(\w+)\s*;", text)
    package = package.group(1) if package else ""
    structs = []
    for m in re.finditer(r"\bstruct\s+(\w+)\s*\{(.*?)\}", text, flags=re.S):
        name, body = m.group(1), m.group(2)
        fields = []
        for decl in body.split(";"):
            decl = decl.strip()
            if not decl or decl.startswith("const "):
                continue
            fm = re.fullmatch(r"([\w.]+)\s+(\w+)\s*((?:\[\s*\w+\s*\]\s*)*)", decl, flags=re.S)
            if not fm:
                sys.exit(f"{path}: cannot parse field declaration '{decl}'")
            ftype, fname, dims = fm.group(1), fm.group(2), fm.group(3)
            ftype = ftype.split(".")[-1]
            dims = re.findall(r"\[\s*(\w+)\s*\]", dims)
            fields.append((ftype, fname, dims))
        structs.append((package, name, fields))
    return structs


def min_size(name, types, seen=()):
    """Fewest bytes an encoded value of a type occupies (no fingerprint)."""
    if name in PRIMITIVE_SIZES:
        return PRIMITIVE_SIZES[name]
    if name == "string":
        return 4 + 1
    if name in seen:
        sys.exit(f"recursive LCM type {name}")
    total = 0
    for ftype, _, dims in types[name]:
        count = 1
        for d in dims:
            count *= int(d) if d.isdigit() else 0
        total += count * min_size(ftype, types, seen + (name,))
    return total


def emit_struct(name, fields, types, out):
    out.append(f"inline bool CheckBody_{name}(WireReader& r, std::string* why) {{")
    int_fields = set()
    used_as_dimension = {d for _, _, dims in fields for d in dims if not d.isdigit()}
    for ftype, fname, dims in fields:
        label = f'"{name}.{fname}"'
        if dims:
            count_expr = []
            for d in dims:
                if d.isdigit():
                    count_expr.append(d)
                else:
                    if d not in int_fields:
                        sys.exit(f"{name}.{fname}: dimension {d} is not an earlier integer field")
                    count_expr.append(f"dim_{d}")
            out.append("  {")
            out.append("    int64_t count = 1;")
            for c in count_expr:
                out.append(f"    if (!MultiplyCount(&count, {c}, {label}, why)) return false;")
            if ftype in PRIMITIVE_SIZES:
                out.append(f"    if (!r.Skip(count, {PRIMITIVE_SIZES[ftype]}, {label}, why)) return false;")
            else:
                msize = max(1, min_size(ftype, types))
                out.append(f"    if (!r.Fits(count, {msize}, {label}, why)) return false;")
                out.append("    for (int64_t i = 0; i < count; ++i) {")
                if ftype == "string":
                    out.append(f"      if (!r.SkipString({label}, why)) return false;")
                else:
                    out.append(f"      if (!CheckBody_{ftype}(r, why)) return false;")
                out.append("    }")
            out.append("  }")
        elif ftype in PRIMITIVE_SIZES:
            size = PRIMITIVE_SIZES[ftype]
            if ftype in INTEGER_TYPES and fname in used_as_dimension:
                out.append(f"  int64_t dim_{fname} = 0;")
                out.append(f"  if (!r.ReadInteger({size}, &dim_{fname}, {label}, why)) return false;")
                int_fields.add(fname)
            else:
                out.append(f"  if (!r.Skip(1, {size}, {label}, why)) return false;")
        elif ftype == "string":
            out.append(f"  if (!r.SkipString({label}, why)) return false;")
        else:
            out.append(f"  if (!CheckBody_{ftype}(r, why)) return false;")
    out.append("  return true;")
    out.append("}")
    out.append("")


def load(lcm_files):
    """(types {name: fields}, package, names with nested types before the types that use them)."""
    structs = []
    for f in lcm_files:
        structs.extend(parse(f))
    types = {name: fields for _, name, fields in structs}
    package = structs[0][0] if structs else "minenav"
    order, done = [], set()

    def visit(name):
        if name in done or name not in types:
            return
        done.add(name)
        for ftype, _, _ in types[name]:
            visit(ftype)
        order.append(name)

    for _, name, _ in sorted(structs, key=lambda s: s[1]):
        visit(name)
    return types, package, order


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    out_path, lcm_files = sys.argv[1], sys.argv[2:]
    types, package, order = load(lcm_files)

    out = [
        "// Generated by cmake/lcm_wire_check.py from lcmtypes/*.lcm. Do not edit.",
        "#pragma once",
        "#include <cstdint>",
        "#include <cstring>",
        "#include <string>",
        "",
    ]
    out += [f'#include "{package}/{name}.hpp"' for name in order]
    out += [
        "",
        f"namespace {package}::wire {{",
        "",
        "// Walks an encoded payload without allocating. Every failure sets *why to one line.",
        "class WireReader {",
        " public:",
        "  WireReader(const uint8_t* data, int64_t size) : data_(data), size_(size) {}",
        "  int64_t remaining() const { return size_ - pos_; }",
        "  int64_t position() const { return pos_; }",
        "  // True when `count` elements of `element_size` bytes fit in what remains.",
        "  bool Fits(int64_t count, int64_t element_size, const char* field, std::string* why) const {",
        "    if (count < 0) {",
        "      *why = std::string(field) + \": negative count \" + std::to_string(count);",
        "      return false;",
        "    }",
        "    if (count == 1 && element_size > remaining()) {",
        "      *why = std::string(field) + \": needs \" + std::to_string(element_size) + \" bytes, \" +",
        "             std::to_string(remaining()) + \" remain at byte \" + std::to_string(pos_) + \" (truncated)\";",
        "      return false;",
        "    }",
        "    if (count > remaining() / element_size) {",
        "      *why = std::string(field) + \": \" + std::to_string(count) + \" elements need at least \" +",
        "             std::to_string(element_size) + \" bytes each, \" + std::to_string(remaining()) +",
        "             \" bytes remain at byte \" + std::to_string(pos_) + \" (truncated, or a corrupt count)\";",
        "      return false;",
        "    }",
        "    return true;",
        "  }",
        "  bool Skip(int64_t count, int64_t element_size, const char* field, std::string* why) {",
        "    if (!Fits(count, element_size, field, why)) return false;",
        "    pos_ += count * element_size;",
        "    return true;",
        "  }",
        "  bool ReadInteger(int bytes, int64_t* value, const char* field, std::string* why) {",
        "    if (!Fits(1, bytes, field, why)) return false;",
        "    uint64_t v = 0;",
        "    for (int i = 0; i < bytes; ++i) v = (v << 8) | data_[pos_ + i];",
        "    // Sign-extend from `bytes` bytes.",
        "    const int shift = 64 - 8 * bytes;",
        "    *value = shift == 0 ? static_cast<int64_t>(v) : static_cast<int64_t>(v << shift) >> shift;",
        "    pos_ += bytes;",
        "    return true;",
        "  }",
        "  // An LCM string: int32 length including the terminating NUL, then the bytes. A C string:",
        "  // the NUL ends it and no other byte is NUL (lcm-gen's C++ decode() keeps what follows an",
        "  // inner NUL and its encode() stops there, so such a string changes when passed on; LCM's",
        "  // other languages cut it). Found by the message_decode fuzz target (issue 16).",
        "  bool SkipString(const char* field, std::string* why) {",
        "    int64_t length = 0;",
        "    if (!ReadInteger(4, &length, field, why)) return false;",
        "    if (length < 1) {",
        "      *why = std::string(field) + \": string length \" + std::to_string(length) + \" (must be >= 1)\";",
        "      return false;",
        "    }",
        "    if (!Fits(length, 1, field, why)) return false;",
        "    const uint8_t* text = data_ + pos_;",
        "    if (text[length - 1] != 0 || std::memchr(text, 0, static_cast<size_t>(length - 1)) != nullptr) {",
        "      *why = std::string(field) + \": a string of \" + std::to_string(length - 1) +",
        "             \" bytes with a NUL inside or without its terminating NUL\";",
        "      return false;",
        "    }",
        "    pos_ += length;",
        "    return true;",
        "  }",
        "",
        " private:",
        "  const uint8_t* data_;",
        "  int64_t size_;",
        "  int64_t pos_ = 0;",
        "};",
        "",
        "// count *= factor, refusing negative factors and products past 2^31 (no LCM array",
        "// can hold more elements than a payload has bytes).",
        "inline bool MultiplyCount(int64_t* count, int64_t factor, const char* field, std::string* why) {",
        "  if (factor < 0) {",
        "    *why = std::string(field) + \": negative count \" + std::to_string(factor);",
        "    return false;",
        "  }",
        "  if (factor != 0 && *count > (int64_t{1} << 31) / factor) {",
        "    *why = std::string(field) + \": count \" + std::to_string(factor) + \" is absurd\";",
        "    return false;",
        "  }",
        "  *count *= factor;",
        "  return true;",
        "}",
        "",
    ]
    for name in order:
        emit_struct(name, types[name], types, out)
    out += [
        "// Check<T>(data, size, &why): true when `size` bytes hold a T whose every count fits",
        "// the payload (fingerprint first). decode() is safe to call only after it returned true.",
        "template <typename T>",
        "bool Check(const void* data, int64_t size, std::string* why);",
        "",
    ]
    for name in order:
        out += [
            "template <>",
            f"inline bool Check<{name}>(const void* data, int64_t size, std::string* why) {{",
            "  WireReader r(static_cast<const uint8_t*>(data), size);",
            "  int64_t fingerprint = 0;",
            f'  if (!r.ReadInteger(8, &fingerprint, "{name} fingerprint", why)) return false;',
            f"  if (fingerprint != {name}::getHash()) {{",
            f'    *why = "wrong fingerprint for {name}";',
            "    return false;",
            "  }",
            f"  return CheckBody_{name}(r, why);",
            "}",
            "",
        ]
    out.append(f"}}  // namespace {package}::wire")
    write_if_changed(out_path, "\n".join(out) + "\n")


def write_if_changed(path, text):
    """Writes `text` unless the file already holds it (so what includes it is not rebuilt)."""
    try:
        if open(path, encoding="utf-8").read() == text:
            return
    except OSError:
        pass
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


if __name__ == "__main__":
    main()
