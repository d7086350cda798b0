#pragma once
// What every DICOM reader of io/ shares: attribute values as text and tag
// names for messages, the patient and study a file belongs to, and a quiet
// DCMTK. Declared without DCMTK's headers
// (forward declarations only), so that this installed header needs none.
#include <string>

class DcmDataset;
class DcmItem;
class DcmTagKey;

namespace dfrecon {

/// Two planes closer than this are one (contour planes, image planes):
/// positions are decimal strings, and planning systems write 2.4991 and
/// 2.4992 for one plane.
inline constexpr double kSamePlaneToleranceMm = 0.01;

/// "(gggg,eeee) Name", e.g. "(0020,0032) ImagePositionPatient", as messages
/// name a tag. O(1).
std::string dicomTagName(const DcmTagKey& key);

/// The value of `key` in `item` (not its sub-items), all values joined by
/// backslashes as stored; "" when absent or empty. O(value length).
std::string dicomText(DcmItem& item, const DcmTagKey& key);

/// Converts every string of `dataset` from its SpecificCharacterSet to
/// UTF-8 (nothing to do for ASCII), so that values copied into a file
/// written as ISO_IR 192 (an RTSTRUCT) say the same. Returns "" when done,
/// else what is wrong, naming the tag (an unknown character set: the
/// strings are then left as stored). O(dataset).
std::string convertDicomTextToUtf8(DcmDataset& dataset);

/// Whether `value` can be one value of a text attribute (LO, SH, PN) in a
/// UTF-8 file (ISO_IR 192): well-formed UTF-8 without control characters or
/// backslashes (the value separator). DCMTK's own checker knows only ASCII
/// and Latin-1 and refuses every other non-ASCII byte. O(length).
bool isValidDicomText(const std::string& value);

/// `value` made valid as isValidDicomText requires: control characters,
/// backslashes and bytes that are not part of well-formed UTF-8 become '_'.
/// O(length).
std::string mendedDicomText(std::string value);

/// The Patient and General Study modules' attributes, which an object made
/// to belong with others (an RT Structure Set on a CT) copies from them.
/// Empty where the source leaves an attribute empty or out.
struct DicomPatientStudy {
    std::string patientName, patientId, patientBirthDate, patientSex;
    std::string studyInstanceUid, studyDate, studyTime, studyId, accessionNumber,
        referringPhysicianName, studyDescription;
};

/// Those attributes of `dataset`. O(their length).
DicomPatientStudy dicomPatientStudy(DcmItem& dataset);

/// Turns DCMTK's logger off, once per process: its complaints would go to
/// stderr, and our messages say what matters with the file and tag.
void silenceDcmtkLog();

}  // namespace dfrecon
