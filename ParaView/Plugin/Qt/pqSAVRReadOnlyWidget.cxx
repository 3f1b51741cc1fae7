#include "pqSAVRReadOnlyWidget.h"

#include "pqCoreUtilities.h"
#include "vtkCommand.h"
#include "vtkPVXMLElement.h"
#include "vtkSMBooleanDomain.h"
#include "vtkSMIntVectorProperty.h"
#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMVectorProperty.h"

#include <QColor>
#include <QEvent>
#include <QHBoxLayout>
#include <QLabel>
#include <QPalette>

pqSAVRReadOnlyWidget::pqSAVRReadOnlyWidget(
  vtkSMProxy* proxy, vtkSMProperty* property, QWidget* parent)
  : Superclass(proxy, parent)
{
  this->setProperty(property);
  this->setShowLabel(true);
  if (vtkPVXMLElement* hints = property->GetHints())
  {
    if (vtkPVXMLElement* hint = hints->FindNestedElementByName("SAVRReadOnly"))
    {
      double scale = 1.0;
      if (hint->GetScalarAttribute("scale", &scale))
      {
        this->Scale = scale;
      }
      this->Suffix = QString::fromUtf8(hint->GetAttributeOrDefault("suffix", ""));
      this->Negative = QString::fromUtf8(hint->GetAttributeOrDefault("negative", ""));
    }
  }
  this->Boolean = vtkSMIntVectorProperty::SafeDownCast(property) &&
                  property->FindDomain<vtkSMBooleanDomain>() != nullptr;

  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  this->Label = new QLabel(this);
  this->Label->setObjectName("Value");
  this->Label->setTextInteractionFlags(Qt::TextSelectableByMouse);
  layout->addWidget(this->Label);
  layout->addStretch();

  pqCoreUtilities::connect(property, vtkCommand::ModifiedEvent, this, SLOT(updateText()));
  this->updateText();
}

pqSAVRReadOnlyWidget::~pqSAVRReadOnlyWidget() = default;

void pqSAVRReadOnlyWidget::changeEvent(QEvent* event)
{
  if (event->type() == QEvent::StyleChange)
  {
    const QString plain =
      QString(":disabled { color: %1; }")
        .arg(this->palette().color(QPalette::Active, QPalette::WindowText).name(QColor::HexArgb));
    if (this->styleSheet() != plain)
    {
      this->setStyleSheet(plain); // (a second StyleChange, which finds it set)
    }
  }
  this->Superclass::changeEvent(event);
}

void pqSAVRReadOnlyWidget::updateText()
{
  vtkSMProperty* property = this->property();
  auto* vector = vtkSMVectorProperty::SafeDownCast(property);
  if (!vector || vector->GetNumberOfElements() == 0)
  {
    this->Label->setText(QString());
    return;
  }
  vtkSMPropertyHelper helper(property);
  const double value = helper.GetAsDouble(0);
  QString text;
  if (this->Boolean)
  {
    text = value != 0.0 ? tr("yes") : tr("no");
  }
  else if (value < 0.0 && !this->Negative.isEmpty())
  {
    text = this->Negative;
  }
  else if (vtkSMIntVectorProperty::SafeDownCast(property) && this->Scale == 1.0)
  {
    text = QString::number(helper.GetAsInt(0)) + this->Suffix;
  }
  else
  {
    text = QString::number(value * this->Scale, 'g', 4) + this->Suffix;
  }
  this->Label->setText(text);
}
