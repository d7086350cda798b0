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
