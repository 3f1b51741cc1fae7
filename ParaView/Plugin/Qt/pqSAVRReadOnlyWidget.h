/**
 * @class   pqSAVRReadOnlyWidget
 * @brief   The Properties panel's widget for a SAVR state property: its value as plain text.
 *
 * ParaView draws an information property with the editor of its type, disabled but styled as
 * enabled, so the mapper's state (frames accumulated, frame limit, error estimate...) looked
 * editable. This widget ("savr_read_only", named by `panel_widget` in the plugin's XML) shows the
 * value as a label instead, updated whenever the property's value changes. The property's
 * `<SAVRReadOnly>` hint may give a `scale` (the value is multiplied by it), a `suffix` (units) and
 * the text shown for a `negative` value. Integer properties with a boolean domain read "yes" or
 * "no".
 */
#ifndef pqSAVRReadOnlyWidget_h
#define pqSAVRReadOnlyWidget_h

#include "pqPropertyWidget.h"

#include <QString>

class QLabel;
class vtkSMProperty;
class vtkSMProxy;

class pqSAVRReadOnlyWidget : public pqPropertyWidget
{
  Q_OBJECT
  typedef pqPropertyWidget Superclass;

public:
  pqSAVRReadOnlyWidget(vtkSMProxy* proxy, vtkSMProperty* property, QWidget* parent = nullptr);
  ~pqSAVRReadOnlyWidget() override;

protected:
  /// Keeps the panel's style for disabled information widgets (an editor's background) off:
  /// only the text colour is kept.
  void changeEvent(QEvent* event) override;

private Q_SLOTS:
  void updateText();

private:
  Q_DISABLE_COPY(pqSAVRReadOnlyWidget)

  QLabel* Label = nullptr;
  double Scale = 1.0;
  QString Suffix;
  QString Negative;
  bool Boolean = false;
};

#endif
