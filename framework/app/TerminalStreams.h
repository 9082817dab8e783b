#pragma once
/// \file TerminalStreams.h
/// Everything the commands print through std::cout and std::cerr passes the
/// terminal filter (esif/core/TerminalText.h): a path, label or token of the
/// user's that holds an escape sequence or a C1 control is shown as \xNN
/// instead of acting on the terminal, in error lines, warnings and
/// summaries alike. The progress bar writes its own cursor controls with
/// stdio, past the filter.

namespace esif::app
{
/// Puts the filter between std::cout / std::cerr and their buffers; once
/// per process, before any command prints (a run forked by the run server
/// inherits it).
void filterTerminalStreams();

/// Writes out what the filters hold (an unfinished UTF-8 sequence, shown
/// escaped) and flushes both streams: call before the process ends.
void finishTerminalStreams();

}  // namespace esif::app
