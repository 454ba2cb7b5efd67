#pragma once
/// \file inflated_size.hpp
/// How many bytes a gzip log holds once inflated, for the memory decisions made before a log is
/// read (cli/memory_budget.cpp). The compressed size says nothing about it: text logs compress
/// 5-700x (a 60 MB log in 91 KB, a 1 GiB "gzip bomb" in 1.5 MB), so an estimate from it let a
/// 91 KB file take 776 MB and a bomb end in bad_alloc.

#include <cstdint>
#include <string>

namespace sigmatau {

/// The bytes the gzip file at `path` inflates to (every member), counted by inflating it
/// without parsing, and stopping once more than `stop_after` bytes [>= 0] have come out: the
/// count returned is then > stop_after (a lower bound). The trailer's ISIZE is not used: it is
/// the last member's size modulo 2^32 only. Throws Error when the file cannot be opened and
/// ParseError on corrupt gzip data, as LogReader would.
std::int64_t inflated_bytes(const std::string& path, std::int64_t stop_after);

}  // namespace sigmatau
