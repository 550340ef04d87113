#pragma once
// What a file parser accepts must survive the project's own writer (the file targets): the
// input read and written, then that text read back and written again, must read back the same.
// The writers round numbers (9 or 10 significant digits), so the first text may differ from the
// input; what is written must never change when read and written again.

#include <cstdint>
#include <string>

#include "common/file_io.h"
#include "fuzz/finding.h"

namespace minenav::fuzz {

// parse(text, source) -> T (throws InputError), write(T) -> text, same(T, T) -> bool.
template <typename Parse, typename Write, typename Same>
void CheckWrittenReadsBack(const uint8_t* data, size_t size, const std::string& what, Parse parse, Write write,
                           Same same) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string once;
  try {
    once = write(parse(text, "fuzz"));
  } catch (const InputError&) {
    return;
  }
  const auto read = parse(once, "written");
  if (!same(read, parse(write(read), "written again"))) Fail(what + " written and read back changes:\n" + once);
}

}  // namespace minenav::fuzz
