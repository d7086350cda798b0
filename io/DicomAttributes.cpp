#include "io/DicomAttributes.hpp"

#include <dcmtk/config/osconfig.h>  // first, as DCMTK requires
#include <dcmtk/dcmdata/dctk.h>
#include <dcmtk/oflog/oflog.h>

#include <cstdio>

namespace dfrecon {

std::string dicomTagName(const DcmTagKey& key) {
    char text[16];
    std::snprintf(text, sizeof text, "(%04X,%04X)", key.getGroup(), key.getElement());
    return std::string(text) + " " + DcmTag(key).getTagName();
}

std::string dicomText(DcmItem& item, const DcmTagKey& key) {
    OFString value;
    return item.findAndGetOFStringArray(key, value).good() ? std::string(value.c_str()) : "";
}

std::string convertDicomTextToUtf8(DcmDataset& dataset) {
    const OFCondition status = dataset.convertToUTF8();
    if (status.good()) return "";
    return dicomTagName(DCM_SpecificCharacterSet) + " '" +
           dicomText(dataset, DCM_SpecificCharacterSet) + "' cannot be converted to UTF-8 (" +
           status.text() + ")";
}

namespace {

// Length of the well-formed UTF-8 sequence at text[i] (1 to 4), or 0.
std::size_t utf8SequenceAt(const std::string& text, std::size_t i) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned char lead = byte(i);
    if (lead < 0x80) return 1;
    const std::size_t length = lead >= 0xf0 ? 4 : lead >= 0xe0 ? 3 : lead >= 0xc2 ? 2 : 0;
    if (length == 0 || lead > 0xf4 || i + length > text.size()) return 0;
    for (std::size_t k = 1; k < length; ++k)
        if ((byte(i + k) & 0xc0) != 0x80) return 0;
    // Overlong forms, surrogates and code points past U+10FFFF.
    if ((lead == 0xe0 && byte(i + 1) < 0xa0) || (lead == 0xed && byte(i + 1) >= 0xa0) ||
        (lead == 0xf0 && byte(i + 1) < 0x90) || (lead == 0xf4 && byte(i + 1) >= 0x90))
        return 0;
    return length;
}

bool isControlOrSeparator(char c) {
    const auto byte = static_cast<unsigned char>(c);
    return byte < 0x20 || byte == 0x7f || c == '\\';
}

}  // namespace

bool isValidDicomText(const std::string& value) {
    for (std::size_t i = 0; i < value.size();) {
        const std::size_t length = utf8SequenceAt(value, i);
        if (length == 0 || isControlOrSeparator(value[i])) return false;
        i += length;
    }
    return true;
}

std::string mendedDicomText(std::string value) {
    for (std::size_t i = 0; i < value.size();) {
        const std::size_t length = utf8SequenceAt(value, i);
        if (length == 0 || isControlOrSeparator(value[i])) {
            value[i++] = '_';
            continue;
        }
        i += length;
    }
    return value;
}

DicomPatientStudy dicomPatientStudy(DcmItem& dataset) {
    DicomPatientStudy ps;
    ps.patientName = dicomText(dataset, DCM_PatientName);
    ps.patientId = dicomText(dataset, DCM_PatientID);
    ps.patientBirthDate = dicomText(dataset, DCM_PatientBirthDate);
    ps.patientSex = dicomText(dataset, DCM_PatientSex);
    ps.studyInstanceUid = dicomText(dataset, DCM_StudyInstanceUID);
    ps.studyDate = dicomText(dataset, DCM_StudyDate);
    ps.studyTime = dicomText(dataset, DCM_StudyTime);
    ps.studyId = dicomText(dataset, DCM_StudyID);
    ps.accessionNumber = dicomText(dataset, DCM_AccessionNumber);
    ps.referringPhysicianName = dicomText(dataset, DCM_ReferringPhysicianName);
    ps.studyDescription = dicomText(dataset, DCM_StudyDescription);
    return ps;
}

void silenceDcmtkLog() {
    static const bool once = [] {
        OFLog::getLogger("dcmtk").setLogLevel(OFLogger::OFF_LOG_LEVEL);
        return true;
    }();
    (void)once;
}

}  // namespace dfrecon
