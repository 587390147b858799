#pragma once
// A library of recorded ground motions: the ONE directory reader (a study's [records] directory, `records select
// --directory` and a suite's directory search all list files with record_files_in), the MANIFEST.tsv beside the
// files, and the identity of a recording (event, year, station, component) that record selection uses to refuse
// one recording twice (issue 23 item 7).
//
// Identity, first source that has it:
//   1. the MANIFEST.tsv row of the file in its own directory (tab-separated, a header row naming at least the
//      columns file, event, station, component; year optional) -- ../shared/records/real has one;
//   2. the AT2 header: NGA-West2 line 2 "Imperial Valley-02, 5/19/1940, El Centro Array #9, 180"; NGA-West1
//      line 2 "BORREGO MOUNTAIN 04/09/68 0230, EL CENTRO ARRAY #9, 180 (USGS STATION 117)";
//   3. none: the record is its own recording (a two-column file without a manifest, a synthetic record). Such
//      records are never refused as duplicates; the selection says how many had no identity.
// Two records are ONE RECORDING when event and year agree, the stations agree and the components lie on the same
// horizontal axis. Names are compared after normalisation (case, punctuation and parenthesised remarks dropped):
// "El Centro (Peknold digitization)" is "el centro". Stations agree when one's words begin the other's within the
// same event ("el centro" and "el centro array 9": the 1940 Imperial Valley Irrigation District station is NGA's
// El Centro Array #9), so two digitisations of one motion are found whatever their files are called. The axis of
// a component: an azimuth in degrees modulo 180 (000 and 180 are the N-S axis, 090 and 270 E-W), N/NS/S -> 0,
// E/EW/W -> 90, N45E-style bearings -> their azimuth; other names (LN, TR) compare as text.
#include <map>
#include <string>
#include <vector>

#include "pounding/motion/records.hpp"

namespace pounding {

// Every regular file in `dir` whose extension is .at2 or .txt (any case), sorted by name (byte order). InputError
// (where = `dir`, fix naming `setting`) when `dir` is not a directory or holds no such file.
std::vector<std::string> record_files_in(const std::string& dir, const std::string& setting);

struct RecordIdentity {
  std::string event, station, component;  // as written in the source (for tables)
  int year = 0;                            // 0: unknown
  std::string from;                        // "MANIFEST.tsv:12", "AT2 header line 2"; empty: no identity
  bool known() const { return !from.empty(); }
  std::string event_text() const;          // "Imperial Valley-02 (1940)", "" when unknown
};

// The identity stored in a record's meta (identify_from_manifest or the AT2 reader put it there); synthetic
// records have none (each is its own motion).
RecordIdentity identity_of(const Record& rec);
// The same event (normalised name and year), the same station (see the header), and for same_recording also the
// same axis. False when either is unknown.
bool same_event(const RecordIdentity& a, const RecordIdentity& b);
bool same_station(const RecordIdentity& a, const RecordIdentity& b);
bool same_recording(const RecordIdentity& a, const RecordIdentity& b);

// MANIFEST.tsv rows by directory, read once per directory. annotate() puts the row of rec.source (if its
// directory has a manifest with that file) into rec.meta: event, year, station, component, identity_from.
// A manifest without the columns file, event, station, component is an InputError naming its header line.
class RecordManifests {
 public:
  void annotate(Record& rec);

 private:
  struct Row {
    std::string event, station, component;
    int year = 0, line = 0;
  };
  std::map<std::string, std::map<std::string, Row>> by_dir_;  // directory -> file name -> row
};

// read_record of each path, annotated from the manifests of their directories.
std::vector<Record> read_library(const std::vector<std::string>& paths, const ReadOptions& options);

}  // namespace pounding
