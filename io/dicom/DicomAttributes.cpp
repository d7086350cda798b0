#include "io/dicom/DicomAttributes.hpp"

#include <dcmtk/config/osconfig.h>  // first, as DCMTK requires
#include <dcmtk/dcmdata/dctk.h>
#include <dcmtk/oflog/oflog.h>

#include <cstdio>

#include "io/files/TextEncoding.hpp"

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

bool isControlOrSeparator(char c) {
    const auto byte = static_cast<unsigned char>(c);
    return byte < 0x20 || byte == 0x7f || c == '\\';
}

}  // namespace

bool isValidDicomText(const std::string& value) {
    for (std::size_t i = 0; i < value.size();) {
        const std::size_t length = utf8SequenceLength(value, i);
        if (length == 0 || isControlOrSeparator(value[i])) return false;
        i += length;
    }
    return true;
}

std::string mendedDicomText(std::string value) {
    for (std::size_t i = 0; i < value.size();) {
        const std::size_t length = utf8SequenceLength(value, i);
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
